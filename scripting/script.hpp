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
  // A warning for each variable given with -v that the script never read (and that the
  // first run has not already warned about).
  std::vector<std::string> unread_variable_warnings();
  // Whether the script read var.NAME (given with -v or not).
  bool reads_variable(const std::string& name) const;

  struct State;

 private:
  std::unique_ptr<State> state_;
};

}  // namespace pbf
