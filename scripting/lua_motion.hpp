#pragma once
// Motions of solids from a script: a Lua function of time, or `pbf.keyframes{...}`, both
// turned into engine Motions (engine/geometry/motion.hpp) that a fix's `motion` parameter takes.
#include <lua.hpp>

#include "engine/registry/params.hpp"
#include "scripting/lua_function.hpp"

namespace pbf::lua {

// A function as a Motion: each call of at(t) calls it with t and reads the table it returns,
// {translate = {x, y, z}, rotate = {rx, ry, rz}} (either may be left out).
MotionPtr function_motion(std::shared_ptr<const FunctionRef> function);

// The Motion held by the value at `index` if it is one pbf.keyframes made, else nullptr.
MotionPtr motion_value(lua_State* L, int index);

// pbf.keyframes{ {t = 0, translate = {...}, rotate = {...}}, ..., interpolation = "spline" }
int l_keyframes(lua_State* L);

}  // namespace pbf::lua
