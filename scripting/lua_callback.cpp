#include "scripting/lua_callback.hpp"

#include <fmt/format.h>

#include "engine/core/error.hpp"
#include "engine/core/simulation.hpp"
#include "scripting/lua_util.hpp"

namespace pbf::lua {

namespace {

class LuaCallback : public Fix {
 public:
  LuaCallback(lua_State* L, const std::string& id, std::int64_t every)
      : Fix(id, "lua"), L_(L), every_(every), ref_(luaL_ref(L, LUA_REGISTRYINDEX)) {}
  ~LuaCallback() override { luaL_unref(L_, LUA_REGISTRYINDEX, ref_); }

  std::vector<Stage> stages() const override { return {Stage::end_of_step}; }
  // Every rank runs the script and its callbacks, at the same steps; the computes they read
  // are collective and give every rank the same values.
  bool runs_distributed() const override { return true; }

  void end_of_step(Simulation& sim) override {
    if (sim.step() % every_ != 0) return;
    lua_rawgeti(L_, LUA_REGISTRYINDEX, ref_);
    lua_pushinteger(L_, static_cast<lua_Integer>(sim.step()));
    lua_pushnumber(L_, sim.time());
    if (lua::pcall(L_, 2, 0) != LUA_OK) {
      // The message handler has made the error a string that says FILE:LINE.
      throw Error(lua::pop_error(L_), true);
    }
  }

 private:
  lua_State* L_;
  std::int64_t every_;
  int ref_;
};

}  // namespace

std::unique_ptr<Fix> make_callback_fix(lua_State* L, const std::string& id, std::int64_t every) {
  if (every < 1) {
    lua_pop(L, 1);
    throw Error(fmt::format("pbf.every: the interval must be at least 1 step, got {}", every));
  }
  return std::make_unique<LuaCallback>(L, id, every);
}

}  // namespace pbf::lua
