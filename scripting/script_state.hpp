#pragma once
// What the functions of the `pbf` table share (scripting/ only): the script's state, reached
// through each function's upvalue, and the table-argument reader.
#include <fmt/format.h>
#include <lua.hpp>
#include <map>
#include <optional>
#include <vector>

#include "engine/core/error.hpp"
#include "engine/core/interrupt.hpp"
#include "engine/registry/params.hpp"
#include "scripting/lua_util.hpp"
#include "scripting/script.hpp"

namespace pbf {

class Simulation;

struct Script::State {
  Simulation& sim;
  lua_State* L = nullptr;
  bool running = false;
  std::map<std::string, bool> variable_read;
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

// The scene functions (domain, kernel_radius, timestep, rest_density, lattice, read_scene,
// read_particles, write_restart, read_restart), scripting/lua_scene.cpp.
std::vector<luaL_Reg> scene_functions();

}  // namespace lua
}  // namespace pbf
