#pragma once
// What the functions of the `pbf` table share (scripting/ only): the script's state, reached
// through each function's upvalue, and the table-argument reader.
#include <fmt/format.h>
#include <lua.hpp>
#include <map>
#include <optional>
#include <set>
#include <vector>

#include "engine/core/error.hpp"
#include "engine/core/interrupt.hpp"
#include "engine/registry/params.hpp"
#include "scripting/lua_util.hpp"
#include "scripting/script.hpp"

namespace pbf {

class Simulation;

struct Script::State {
  explicit State(Simulation& simulation) : sim(simulation) {}
  Simulation& sim;
  lua_State* L = nullptr;
  bool running = false;
  std::string script_path;
  std::map<std::string, bool> variable_read;    // each -v variable: read yet?
  std::set<std::string> variables_looked_up;    // every name the script read from var
  std::set<std::string> unread_reported;        // unread variables already warned about
  bool variables_checked = false;               // by the first run
  std::optional<Interrupted> interrupted;  // a run stopped by Ctrl-C: the script ends

  // Changing the scene or the pipeline from a callback inside a run is not allowed.
  void not_running(const char* function) const {
    if (running) throw Error(fmt::format("{} cannot be called during a run (from a pbf.every callback)", function));
  }
};

namespace lua {

using State = Script::State;

inline State& state(lua_State* L) { return *static_cast<State*>(lua_touserdata(L, lua_upvalueindex(1))); }

// Checks a table argument against a schema, like style parameters.
inline Params table_arg(lua_State* L, int index, const char* function, const std::vector<ParamSpec>& schema) {
  if (lua_type(L, index) != LUA_TTABLE) throw Error(fmt::format("{} takes a table {{name = value, ...}}", function));
  return Params(function, schema, lua::table_params(L, index, function));
}

// The var table (scripting/lua_variables.cpp).
void install_variables(lua_State* L, State& S, const std::vector<std::pair<std::string, std::string>>& variables);
// At the first run's start: refuses a -v restart the script has not read, warns about the
// unread variables that look like typos.
void check_variables_at_first_run(State& S);
// "variable 'NAME' given with -v VERB by SCRIPT WHEN (did you mean ...)" for each unread
// variable not reported yet (with typos_only, those close to a name the script read).
std::vector<std::string> report_unread_variables(State& S, const char* verb, const char* when, bool typos_only);

// The scene functions (domain, kernel_radius, timestep, rest_density, lattice, read_scene,
// read_particles, write_restart, read_restart), scripting/lua_scene.cpp.
std::vector<luaL_Reg> scene_functions();

}  // namespace lua
}  // namespace pbf
