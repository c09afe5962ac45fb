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
  explicit FunctionMotion(std::shared_ptr<const FunctionRef> function) : function_(std::move(function)) {}

  Pose at(double t) const override {
    const std::string what = fmt::format("the motion function ({}) at t = {}", function_->where(), t);
    lua_State* L = function_->push();
    lua_pushnumber(L, t);
    if (pcall(L, 1, 1) != LUA_OK) throw Error(fmt::format("{}: {}", what, pop_error(L)), true);
    if (lua_type(L, -1) != LUA_TTABLE) {
      const std::string type = luaL_typename(L, -1);
      lua_pop(L, 1);
      throw Error(fmt::format("{} returned a {}, not a table {{translate = {{x, y, z}}, rotate = {{rx, ry, rz}}}}",
                              what, type));
    }
    Pose pose;
    const int table = lua_gettop(L);
    try {
      optional_vec3(L, table, "translate", pose.translate, what);
      optional_vec3(L, table, "rotate", pose.rotate_deg, what);
    } catch (...) {
      lua_pop(L, 1);
      throw;
    }
    lua_pop(L, 1);
    check_pose(pose, what);
    return pose;
  }

  std::string description() const override { return fmt::format("function ({})", function_->where()); }

 private:
  std::shared_ptr<const FunctionRef> function_;
};

}  // namespace

MotionPtr function_motion(std::shared_ptr<const FunctionRef> function) {
  return std::make_shared<FunctionMotion>(std::move(function));
}

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
