#include "scripting/lua_motion.hpp"

#include <cmath>
#include <fmt/format.h>
#include <memory>

#include "engine/core/error.hpp"
#include "engine/geometry/motion.hpp"
#include "scripting/lua_util.hpp"

namespace pbf::lua {

namespace {

constexpr const char* kMotionType = "pbf.motion";
const char alive_key = 0;  // its address keys the state's "alive" flag in the registry

// A flag that stays true while the Lua state is open: a motion a fix still holds after the
// script's state has closed (an error ends the script before the simulation is destroyed)
// must not touch it. The flag's userdata is collected when the state closes, and its __gc
// clears the flag.
std::shared_ptr<bool> state_alive(lua_State* L) {
  lua_rawgetp(L, LUA_REGISTRYINDEX, &alive_key);
  if (auto* held = static_cast<std::shared_ptr<bool>*>(lua_touserdata(L, -1))) {
    std::shared_ptr<bool> alive = *held;
    lua_pop(L, 1);
    return alive;
  }
  lua_pop(L, 1);
  auto* held = new (lua_newuserdatauv(L, sizeof(std::shared_ptr<bool>), 0)) std::shared_ptr<bool>(std::make_shared<bool>(true));
  lua_createtable(L, 0, 1);
  lua_pushcfunction(L, [](lua_State* S) {
    auto* flag = static_cast<std::shared_ptr<bool>*>(lua_touserdata(S, 1));
    **flag = false;
    flag->~shared_ptr();
    return 0;
  });
  lua_setfield(L, -2, "__gc");
  lua_setmetatable(L, -2);
  lua_rawsetp(L, LUA_REGISTRYINDEX, &alive_key);
  return *held;
}

// Reads the optional vector `key` of the table at `index` into `out` (zeros when absent).
void optional_vec3(lua_State* L, int index, const char* key, std::array<double, 3>& out, const std::string& what) {
  lua_getfield(L, index, key);
  if (!lua_isnil(L, -1)) {
    try {
      const Vec3 v = vec3(L, -1, fmt::format("{}: '{}'", what, key).c_str());
      out = {v[0], v[1], v[2]};
    } catch (...) {
      lua_pop(L, 1);
      throw;
    }
  }
  lua_pop(L, 1);
}

class FunctionMotion : public Motion {
 public:
  FunctionMotion(lua_State* L, int index) : L_(L), alive_(state_alive(L)) {
    lua_Debug ar;
    lua_pushvalue(L, index);
    lua_getinfo(L, ">S", &ar);  // pops the function
    where_ = ar.linedefined > 0 ? fmt::format("{}:{}", ar.short_src, ar.linedefined) : std::string(ar.short_src);
    lua_pushvalue(L, index);
    ref_ = luaL_ref(L, LUA_REGISTRYINDEX);
  }
  ~FunctionMotion() override {
    if (*alive_) luaL_unref(L_, LUA_REGISTRYINDEX, ref_);
  }

  Pose at(double t) const override {
    if (!*alive_) throw Error("a motion function outlived its script");
    const std::string what = fmt::format("the motion function ({}) at t = {}", where_, t);
    lua_rawgeti(L_, LUA_REGISTRYINDEX, ref_);
    lua_pushnumber(L_, t);
    if (pcall(L_, 1, 1) != LUA_OK) throw Error(fmt::format("{}: {}", what, pop_error(L_)), true);
    if (lua_type(L_, -1) != LUA_TTABLE) {
      const std::string type = luaL_typename(L_, -1);
      lua_pop(L_, 1);
      throw Error(fmt::format("{} returned a {}, not a table {{translate = {{x, y, z}}, rotate = {{rx, ry, rz}}}}",
                              what, type));
    }
    Pose pose;
    const int table = lua_gettop(L_);
    try {
      optional_vec3(L_, table, "translate", pose.translate, what);
      optional_vec3(L_, table, "rotate", pose.rotate_deg, what);
    } catch (...) {
      lua_pop(L_, 1);
      throw;
    }
    lua_pop(L_, 1);
    for (int c = 0; c < 6; ++c) {
      const double v = c < 3 ? pose.translate[c] : pose.rotate_deg[c - 3];
      if (!std::isfinite(v) || std::abs(v) > 1e6)
        throw Error(fmt::format("{} returned {}[{}] = {}: a pose needs finite numbers of magnitude at most 1e6", what,
                                c < 3 ? "translate" : "rotate", c % 3 + 1, std::isnan(v) ? "nan" : fmt::format("{}", v)));
    }
    return pose;
  }

  std::string description() const override { return fmt::format("function ({})", where_); }

 private:
  lua_State* L_;
  std::shared_ptr<bool> alive_;
  int ref_;
  std::string where_;
};

}  // namespace

MotionPtr function_motion(lua_State* L, int index) { return std::make_shared<FunctionMotion>(L, lua_absindex(L, index)); }

MotionPtr motion_value(lua_State* L, int index) {
  auto* held = static_cast<MotionPtr*>(luaL_testudata(L, index, kMotionType));
  return held ? *held : nullptr;
}

int l_keyframes(lua_State* L) {
  const std::string what = "pbf.keyframes";
  if (lua_type(L, 1) != LUA_TTABLE)
    throw Error("pbf.keyframes takes a table of keys {{t = T, translate = {x, y, z}, rotate = {rx, ry, rz}}, ...}");
  // The keys and the one option.
  lua_pushnil(L);
  while (lua_next(L, 1)) {
    const bool option = lua_type(L, -2) == LUA_TSTRING && std::string(lua_tostring(L, -2)) == "interpolation";
    const bool index = lua_isinteger(L, -2);
    lua_pop(L, 1);
    if (!option && !index) {
      const std::string key = lua_type(L, -1) == LUA_TSTRING ? lua_tostring(L, -1) : luaL_typename(L, -1);
      lua_pop(L, 1);
      throw Error(fmt::format("{}: unknown entry '{}'; it takes keys in a list and 'interpolation'", what, key));
    }
  }
  auto interpolation = Keyframes::Interpolation::linear;
  lua_getfield(L, 1, "interpolation");
  if (!lua_isnil(L, -1)) {
    const std::string name = string(L, -1, "pbf.keyframes: 'interpolation'");
    if (name == "spline") interpolation = Keyframes::Interpolation::spline;
    else if (name != "linear") {
      lua_pop(L, 1);
      throw Error(fmt::format("{}: 'interpolation' must be \"linear\" or \"spline\", got \"{}\"", what, name));
    }
  }
  lua_pop(L, 1);
  std::vector<Keyframes::Key> keys;
  const auto n = static_cast<lua_Integer>(lua_rawlen(L, 1));
  for (lua_Integer k = 1; k <= n; ++k) {
    const std::string key_what = fmt::format("{}: key {}", what, k);
    lua_rawgeti(L, 1, k);
    if (lua_type(L, -1) != LUA_TTABLE) {
      lua_pop(L, 1);
      throw Error(fmt::format("{} must be a table {{t = T, translate = {{x, y, z}}, rotate = {{rx, ry, rz}}}}", key_what));
    }
    const int table = lua_gettop(L);
    Keyframes::Key key;
    try {
      lua_getfield(L, table, "t");
      key.t = number(L, -1, fmt::format("{}: 't'", key_what).c_str());
      lua_pop(L, 1);
      optional_vec3(L, table, "translate", key.pose.translate, key_what);
      optional_vec3(L, table, "rotate", key.pose.rotate_deg, key_what);
    } catch (...) {
      lua_settop(L, table - 1);
      throw;
    }
    lua_pop(L, 1);
    keys.push_back(key);
  }
  MotionPtr motion = std::make_shared<Keyframes>(std::move(keys), interpolation, what);
  void* memory = lua_newuserdatauv(L, sizeof(MotionPtr), 0);
  new (memory) MotionPtr(std::move(motion));
  if (luaL_newmetatable(L, kMotionType)) {
    lua_pushcfunction(L, [](lua_State* S) {
      static_cast<MotionPtr*>(lua_touserdata(S, 1))->~MotionPtr();
      return 0;
    });
    lua_setfield(L, -2, "__gc");
    lua_pushcfunction(L, [](lua_State* S) {
      const MotionPtr& m = *static_cast<MotionPtr*>(lua_touserdata(S, 1));
      lua_pushstring(S, m->description().c_str());
      return 1;
    });
    lua_setfield(L, -2, "__tostring");
  }
  lua_setmetatable(L, -2);
  return 1;
}

}  // namespace pbf::lua
