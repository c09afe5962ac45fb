#pragma once
// Runs a Lua 5.4 scenario script against a Simulation: the global `pbf` table binds the
// engine, the global `var` table holds the command line's -v variables. The only part of
// pbfengine that knows Lua.
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace pbf {

class Simulation;

class Script {
 public:
  explicit Script(Simulation& sim);
  ~Script();
  Script(const Script&) = delete;
  Script& operator=(const Script&) = delete;

  // -v NAME=VALUE pairs; values are converted as Lua converts numerals.
  void set_variables(const std::vector<std::pair<std::string, std::string>>& variables);
  // Runs the file; throws pbf::Error with the one-line "FILE:LINE: message".
  void run_file(const std::string& path);
  // Runs Lua statements as a chunk called `name` (messages say "NAME:LINE: ...").
  void run_text(const std::string& text, const std::string& name);
  // A warning for each variable given with -v that the script never read (and that the
  // first run has not already warned about).
  std::vector<std::string> unread_variable_warnings();
  // Ctrl-C while the script's own Lua code runs (not a run, which stops after its step) ends
  // the script with the error "interrupted (Ctrl-C)", as Lua's own interpreter does: for the
  // Python module, whose process goes on. (The command line leaves Ctrl-C ending the process.)
  void set_interruptible(bool interruptible) { interruptible_ = interruptible; }
  // Whether the script read var.NAME (given with -v or not).
  bool reads_variable(const std::string& name) const;

  struct State;

 private:
  void run_chunk(const std::string& text, const std::string& path);
  std::unique_ptr<State> state_;
  bool interruptible_ = false;
};

}  // namespace pbf
