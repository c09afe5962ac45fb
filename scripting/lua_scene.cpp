// The scene functions of the `pbf` table: the domain and settings, particles from lattices
// and files, and restarts.
#include <cmath>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "engine/io/load_particles.hpp"
#include "engine/io/restart.hpp"
#include "engine/io/scene_file.hpp"
#include "engine/core/scene_commands.hpp"
#include "engine/core/simulation.hpp"
#include "scripting/script_state.hpp"

namespace pbf::lua {

namespace {

void push_vec3(lua_State* L, const double v[3]) {
  lua_createtable(L, 3, 0);
  for (int k = 0; k < 3; ++k) {
    lua_pushnumber(L, v[k]);
    lua_rawseti(L, -2, k + 1);
  }
}

int l_domain(lua_State* L) {
  State& S = state(L);
  if (!lua_isnoneornil(L, 1)) {
    S.not_running("pbf.domain");
    S.sim.set_domain(domain_from(table_arg(L, 1, "pbf.domain", domain_params())));
  }
  const Domain& d = S.sim.domain();
  lua_createtable(L, 0, 3);
  push_vec3(L, d.lo);
  lua_setfield(L, -2, "lo");
  push_vec3(L, d.hi);
  lua_setfield(L, -2, "hi");
  lua_createtable(L, 3, 0);  // the periodic axes' names
  for (int a = 0, k = 0; a < 3; ++a)
    if (d.periodic[a]) {
      lua_pushstring(L, std::string(1, "xyz"[a]).c_str());
      lua_rawseti(L, -2, ++k);
    }
  lua_setfield(L, -2, "periodic");
  return 1;
}

// Getter/setter pairs: pbf.kernel_radius(h) sets, pbf.kernel_radius() reads.
constexpr char kKernelRadius[] = "pbf.kernel_radius", kTimestep[] = "pbf.timestep", kRestDensity[] = "pbf.rest_density";
template <double (Simulation::*Get)() const, void (Simulation::*Set)(double), const char* Name>
int l_setting(lua_State* L) {
  State& S = state(L);
  if (!lua_isnoneornil(L, 1)) {
    S.not_running(Name);
    (S.sim.*Set)(lua::number(L, 1, fmt::format("{}: the value", Name).c_str()));
  }
  lua_pushnumber(L, (S.sim.*Get)());
  return 1;
}

// Gives particles [first, end) the velocity the Lua function at `function` returns for each
// one's position: velocity = function(x, y, z) return {vx, vy, vz} end.
void velocities_from_function(lua_State* L, int function, Particles& P, std::size_t first) {
  for (std::size_t i = first; i < P.size(); ++i) {
    const double q[3] = {P.x()[i], P.y()[i], P.z()[i]};
    const std::string what =
        fmt::format("pbf.lattice: the velocity function at ({:.6g}, {:.6g}, {:.6g})", q[0], q[1], q[2]);
    lua_pushvalue(L, function);
    for (double c : q) lua_pushnumber(L, c);
    if (pcall(L, 3, 1) != LUA_OK) throw Error(fmt::format("{} failed: {}", what, pop_error(L)));
    Vec3 v;
    try {
      v = vec3(L, -1, fmt::format("{}: its result", what).c_str());
    } catch (...) {
      lua_pop(L, 1);
      throw;
    }
    lua_pop(L, 1);
    for (double c : v)
      if (!std::isfinite(c)) throw Error(fmt::format("{} returned a velocity that is not finite", what));
    P.vx()[i] = real(v[0]);
    P.vy()[i] = real(v[1]);
    P.vz()[i] = real(v[2]);
  }
}

int l_lattice(lua_State* L) {
  State& S = state(L);
  S.not_running("pbf.lattice");
  // `velocity` may be a function of position: held aside while the table's other entries are
  // read, and put back.
  int velocity_function = 0;
  if (lua_istable(L, 1)) {
    lua_getfield(L, 1, "velocity");
    if (lua_isfunction(L, -1)) {
      velocity_function = lua_gettop(L);
      lua_pushnil(L);
      lua_setfield(L, 1, "velocity");
    } else {
      lua_pop(L, 1);
    }
  }
  const LatticeAdded added = lattice_command(S.sim, table_arg(L, 1, "pbf.lattice", lattice_params()), "pbf.lattice");
  if (velocity_function) {
    lua_pushvalue(L, velocity_function);
    lua_setfield(L, 1, "velocity");
    velocities_from_function(L, velocity_function, S.sim.particles(), added.first);
  }
  lua_pushinteger(L, static_cast<lua_Integer>(added.added));
  return 1;
}

// pbf.delete{region = ..., ...}: removes the particles inside a region (engine/geometry/region.hpp)
// and returns how many; the others keep their ids.
int l_delete(lua_State* L) {
  State& S = state(L);
  S.not_running("pbf.delete");
  const std::size_t removed = delete_command(S.sim, table_arg(L, 1, "pbf.delete", delete_params()));
  lua_pushinteger(L, static_cast<lua_Integer>(removed));
  return 1;
}

int l_read_scene(lua_State* L) {
  State& S = state(L);
  S.not_running("pbf.read_scene");
  if (S.sim.global_count() > 0)
    throw Error("pbf.read_scene: the scene file sets the domain, so read it before creating any particle");
  const SceneFile scene = read_scene_file(lua::path(L, 1, "pbf.read_scene: the path"));
  const double mass = load_scene(S.sim, scene);
  lua_createtable(L, 0, 7);
  const std::pair<const char*, double> fields[] = {{"dt", scene.dt},         {"h", scene.h},
                                                   {"L", scene.L},           {"interval", scene.interval},
                                                   {"t_final", scene.t_final}, {"mass", mass}};
  for (const auto& [name, value] : fields) {
    lua_pushnumber(L, value);
    lua_setfield(L, -2, name);
  }
  lua_pushinteger(L, static_cast<lua_Integer>(scene.count));
  lua_setfield(L, -2, "count");
  return 1;
}

int l_read_particles(lua_State* L) {
  State& S = state(L);
  S.not_running("pbf.read_particles");
  const std::string path = lua::path(L, 1, "pbf.read_particles: the path");
  const LoadedParticles loaded = load_particle_file(S.sim, path);
  if (!loaded.ignored.empty()) {
    std::string names;
    for (const auto& n : loaded.ignored) names += (names.empty() ? "" : ", ") + n;
    spdlog::info("{}: columns not used: {}", path, names);
  }
  lua_createtable(L, 0, 2);
  lua_pushinteger(L, static_cast<lua_Integer>(loaded.count));
  lua_setfield(L, -2, "count");
  lua_pushnumber(L, loaded.mass);
  lua_setfield(L, -2, "mass");
  return 1;
}

void push_restart_summary(lua_State* L, const RestartSummary& r) {
  lua_createtable(L, 0, 4);
  lua_pushinteger(L, static_cast<lua_Integer>(r.step));
  lua_setfield(L, -2, "step");
  lua_pushnumber(L, r.time);
  lua_setfield(L, -2, "time");
  lua_pushinteger(L, static_cast<lua_Integer>(r.particles));
  lua_setfield(L, -2, "particles");
  lua_pushinteger(L, static_cast<lua_Integer>(r.bytes));
  lua_setfield(L, -2, "bytes");
  lua_pushnumber(L, r.seconds);
  lua_setfield(L, -2, "seconds");
}

int l_write_restart(lua_State* L) {
  State& S = state(L);
  S.not_running("pbf.write_restart");
  const std::string path = lua::path(L, 1, "pbf.write_restart: the path");
  // (A scene drained of its particles, or waiting for an emitter's, is saved: it runs on.)
  if (S.sim.particle_mass() == 0) throw Error("pbf.write_restart: there are no particles to save");
  push_restart_summary(L, write_restart(S.sim, path));
  return 1;
}

int l_read_restart(lua_State* L) {
  State& S = state(L);
  S.not_running("pbf.read_restart");
  if (S.sim.global_count() > 0)
    throw Error("pbf.read_restart replaces the scene: call it before creating any particle");
  push_restart_summary(L, read_restart(S.sim, lua::path(L, 1, "pbf.read_restart: the path")));
  return 1;
}

// pbf.scene(build): builds the scene with the function, or, when the command line gives
// -v restart=FILE, reads it from that restart and does not call the function (LAMMPS's
// read_restart in place of the scene's commands). So one script starts a run and continues
// it: the pipeline that follows is declared either way.
int l_scene(lua_State* L) {
  State& S = state(L);
  S.not_running("pbf.scene");
  if (lua_type(L, 1) != LUA_TFUNCTION)
    throw Error("pbf.scene takes the function that builds the scene: pbf.scene(function() ... end)");
  if (S.sim.global_count() > 0)
    throw Error("pbf.scene builds the scene or reads it from a restart: call it before creating any particle");
  lua_getglobal(L, "var");
  lua_getfield(L, -1, "restart");  // through var's __index: the variable counts as read
  if (!lua_isnil(L, -1)) {
    const std::string path = lua::path(L, -1, "pbf.scene: var.restart");
    lua_pop(L, 2);
    const RestartSummary r = read_restart(S.sim, path);
    spdlog::info("continuing from {}: step {}, t = {} s, {} particles", path, r.step, r.time, r.particles);
    push_restart_summary(L, r);
    lua_pushstring(L, path.c_str());
    lua_setfield(L, -2, "restart");
    return 1;
  }
  lua_pop(L, 2);
  lua_pushvalue(L, 1);
  if (pcall(L, 0, 0) != LUA_OK) {
    if (S.interrupted) throw *S.interrupted;
    throw Error(pop_error(L), true);  // the message names the line inside the function
  }
  lua_createtable(L, 0, 3);
  lua_pushinteger(L, static_cast<lua_Integer>(S.sim.step()));
  lua_setfield(L, -2, "step");
  lua_pushnumber(L, S.sim.time());
  lua_setfield(L, -2, "time");
  lua_pushinteger(L, static_cast<lua_Integer>(S.sim.global_count()));
  lua_setfield(L, -2, "particles");
  return 1;
}

}  // namespace

std::vector<luaL_Reg> scene_functions() {
  return {{"domain", guarded<l_domain>},
          {"kernel_radius", guarded<l_setting<&Simulation::kernel_radius, &Simulation::set_kernel_radius, kKernelRadius>>},
          {"timestep", guarded<l_setting<&Simulation::timestep, &Simulation::set_timestep, kTimestep>>},
          {"rest_density", guarded<l_setting<&Simulation::rest_density, &Simulation::set_rest_density, kRestDensity>>},
          {"lattice", guarded<l_lattice>},
          {"delete", guarded<l_delete>},
          {"read_scene", guarded<l_read_scene>},
          {"read_particles", guarded<l_read_particles>},
          {"write_restart", guarded<l_write_restart>},
          {"read_restart", guarded<l_read_restart>},
          {"scene", guarded<l_scene>}};
}

}  // namespace pbf::lua
