#pragma once
// What a run prints: the console (info lines on stdout, warnings and errors on stderr) and
// the log file of `pbfengine run` (log.pbfengine by default, as LAMMPS's log.lammps), a copy
// of everything the run prints, info lines, warnings, Lua's print and the final error, in
// the order printed. One per process; writing without an open log does nothing.
#include <functional>
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

// The engine's logger (spdlog's default) at this level (trace ... off): each line to the
// console and the log file, warnings and errors prefixed "warning: " and "error: ".
void setup_logging(const std::string& level);
// Writes text to the console: stdout, or stderr for warnings and errors, flushed.
void console(std::string_view text, bool error);
// Where console() writes instead (the Python module: Python's sys.stdout and sys.stderr, so
// a notebook shows the lines); an empty function restores stdout and stderr.
void set_console(std::function<void(std::string_view text, bool error)> writer);

}  // namespace pbf::log_file
