#pragma once
// A scripted fix: calls a Lua function every N steps at the end of the step, with the step
// number and time as arguments. Slow next to native fixes (a Lua call, and whatever the
// function does): meant for monitoring, printing and steering, not for per-particle work.
#include <lua.hpp>
#include <memory>

#include "engine/core/fix.hpp"

namespace pbf::lua {

// Takes the function on top of the Lua stack (pops it).
std::unique_ptr<Fix> make_callback_fix(lua_State* L, const std::string& id, std::int64_t every);

}  // namespace pbf::lua
