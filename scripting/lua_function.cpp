#include "scripting/lua_function.hpp"

#include <fmt/format.h>

#include "engine/core/error.hpp"
#include "engine/geometry/space_time_function.hpp"
#include "scripting/lua_motion.hpp"
#include "scripting/lua_util.hpp"

namespace pbf::lua {

namespace {

const char alive_key = 0;  // its address keys the state's "alive" flag in the registry

// A flag that stays true while the Lua state is open. The flag's userdata is collected when
// the state closes, and its __gc clears the flag.
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

// function(t, x, y, z) returning a number (components 1) or a vector {a, b, c} (3). Only the
// form of what it returns is checked here; what the values mean, the caller checks.
class LuaSpaceTime : public SpaceTimeFunction {
 public:
  LuaSpaceTime(std::shared_ptr<const FunctionRef> function, int components)
      : function_(std::move(function)), components_(components) {}

  Vec3 at(double t, const Vec3& x) const override {
    lua_State* L = function_->push();
    lua_pushnumber(L, t);
    for (double c : x) lua_pushnumber(L, c);
    if (pcall(L, 4, 1) != LUA_OK) throw Error(fmt::format("{}: {}", what(t, x), pop_error(L)), true);
    Vec3 value{0, 0, 0};
    const std::string wrong = components_ == 1 ? read_number(L, value) : read_vector(L, value);
    lua_pop(L, 1);
    if (!wrong.empty()) throw Error(fmt::format("{} {}", what(t, x), wrong));
    return value;
  }
  bool constant() const override { return false; }
  std::string description() const override { return fmt::format("the function ({})", function_->where()); }

 private:
  std::string what(double t, const Vec3& x) const {
    return fmt::format("{} at t = {} s, (x, y, z) = ({:.6g}, {:.6g}, {:.6g})", description(), t, x[0], x[1], x[2]);
  }
  // What is wrong with the result on top of the stack ("" when nothing is), read into value.
  static std::string read_number(lua_State* L, Vec3& value) {
    if (lua_type(L, -1) != LUA_TNUMBER) return fmt::format("returned a {}, not a number", luaL_typename(L, -1));
    value[0] = lua_tonumber(L, -1);
    return "";
  }
  static std::string read_vector(lua_State* L, Vec3& value) {
    if (lua_type(L, -1) != LUA_TTABLE)
      return fmt::format("returned a {}, not a vector {{x, y, z}}", luaL_typename(L, -1));
    const auto n = lua_rawlen(L, -1);
    if (n != 3) return fmt::format("returned a table of {} values, not a vector {{x, y, z}}", n);
    for (int k = 0; k < 3; ++k) {
      lua_rawgeti(L, -1, k + 1);
      const bool ok = lua_type(L, -1) == LUA_TNUMBER;
      const std::string type = luaL_typename(L, -1);
      value[static_cast<std::size_t>(k)] = lua_tonumber(L, -1);
      lua_pop(L, 1);
      if (!ok) return fmt::format("returned a vector whose component {} is a {}, not a number", k + 1, type);
    }
    return "";
  }

  std::shared_ptr<const FunctionRef> function_;
  int components_;
};

class LuaFunction : public ScriptFunction {
 public:
  explicit LuaFunction(std::shared_ptr<const FunctionRef> function) : function_(std::move(function)) {}
  MotionPtr motion() const override { return function_motion(function_); }
  SpaceTimeFunctionPtr of_time_and_place(int components) const override {
    return std::make_shared<LuaSpaceTime>(function_, components);
  }
  std::string description() const override { return fmt::format("defined at {}", function_->where()); }

 private:
  std::shared_ptr<const FunctionRef> function_;
};

}  // namespace

FunctionRef::FunctionRef(lua_State* L, int index) : L_(L), alive_(state_alive(L)) {
  index = lua_absindex(L, index);
  lua_Debug ar;
  lua_pushvalue(L, index);
  lua_getinfo(L, ">S", &ar);  // pops the function
  where_ = ar.linedefined > 0 ? fmt::format("{}:{}", ar.short_src, ar.linedefined) : std::string(ar.short_src);
  lua_pushvalue(L, index);
  ref_ = luaL_ref(L, LUA_REGISTRYINDEX);
}

FunctionRef::~FunctionRef() {
  if (*alive_) luaL_unref(L_, LUA_REGISTRYINDEX, ref_);
}

lua_State* FunctionRef::push() const {
  if (!*alive_) throw Error(fmt::format("the function defined at {} outlived its script", where_));
  lua_rawgeti(L_, LUA_REGISTRYINDEX, ref_);
  return L_;
}

ScriptFunctionPtr script_function(lua_State* L, int index) {
  return std::make_shared<LuaFunction>(std::make_shared<FunctionRef>(L, index));
}

}  // namespace pbf::lua
