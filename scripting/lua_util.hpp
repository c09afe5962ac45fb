#pragma once
// A thin, typed layer over the Lua C API. Argument readers throw pbf::Error (never
// lua_error), so C++ destructors always run; `guarded` turns the exception into one Lua
// error carrying the calling script's FILE:LINE.
#include <lua.hpp>
#include <new>
#include <string>

#include "engine/error.hpp"
#include "engine/params.hpp"

namespace pbf::lua {

// "FILE:LINE: " of the Lua code that called the running C function.
std::string where(lua_State* L);

double number(lua_State* L, int index, const char* what);
std::int64_t integer(lua_State* L, int index, const char* what);
std::string string(lua_State* L, int index, const char* what);
Vec3 vec3(lua_State* L, int index, const char* what);
Names string_list(lua_State* L, int index, const char* what);
// A Lua value converted to a parameter value (number, integer, boolean, string, {x,y,z},
// {"name", ...}).
ParamValue param_value(lua_State* L, int index, const std::string& name);
// The key/value pairs of the table at `index` (absent or nil: none), sorted by key.
GivenParams table_params(lua_State* L, int index, const char* what);

template <int (*F)(lua_State*)>
int guarded(lua_State* L) {
  {
    std::string message;
    try {
      return F(L);
    } catch (const Error& e) {
      message = e.located() ? e.what() : where(L) + e.what();
    } catch (const std::bad_alloc&) {
      message = where(L) + "out of memory";
    } catch (const std::exception& e) {
      message = where(L) + e.what();
    }
    lua_pushlstring(L, message.data(), message.size());
  }  // `message` is destroyed before lua_error jumps
  return lua_error(L);
}

}  // namespace pbf::lua
