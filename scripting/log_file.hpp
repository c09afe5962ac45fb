#pragma once
// The log file of `pbfengine run` (log.pbfengine by default, as LAMMPS's log.lammps): a copy
// of everything the run prints, info lines, warnings, Lua's print and the final error, in
// the order printed. One per process; writing without an open log does nothing.
#include <string>
#include <string_view>

namespace pbf::log_file {

// Opens PATH for writing, replacing any earlier log; returns "" or why it cannot be opened.
std::string open(const std::string& path);
// Appends text as given (lines end with '\n') and flushes, so the log can be followed
// during a run. Safe from any thread.
void write(std::string_view text);
// Closes the log; returns false if any write to it failed (a full disk).
bool close();

}  // namespace pbf::log_file
