#pragma once
// A thin, typed layer over the Lua C API. Argument readers throw pbf::Error (never
// lua_error), so C++ destructors always run; `guarded` turns the exception into one Lua
// error carrying the calling script's FILE:LINE.
#include <climits>
#include <lua.hpp>
#include <new>
#include <string>

#include "engine/core/error.hpp"
#include "engine/registry/params.hpp"

namespace pbf::lua {

// "FILE:LINE: " of the Lua code that called the running C function.
std::string where(lua_State* L);

// For a relative `path` that named no file: where the script that called is, when that is
// not the current folder ("; the script is in DIR"), and the path to give when the file is
// beside the script; else "".
std::string beside_script(lua_State* L, const std::string& path);

// Whether a message already says where, with "CHUNK:LINE:" in its first line (Lua's form,
// and the engine's).
bool has_position(const char* message);

// lua_pcall with a message handler that gives every error a place: an error object that is
// not a string (error({}), error(42)) becomes text (through __tostring if it has one), and
// a message without "FILE:LINE:" (a C stack overflow inside a library function,
// error(msg, 0)) gets the line of the innermost Lua function. Messages the engine raised
// through `guarded` pass unchanged. Calls the function below `nargs` arguments on the stack.
int pcall(lua_State* L, int nargs, int nresults);
// After a failed pcall: the error on top of the stack as text (the message handler makes it a
// string; out of memory aside), popped.
std::string pop_error(lua_State* L);
// Marks the message on top of the stack as the engine's (see pcall); used by `guarded`.
void mark_engine_error(lua_State* L);

// A size for lua_createtable, which takes an int: only a hint, so a larger one is capped.
inline int size_hint(std::size_t n) { return n < static_cast<std::size_t>(INT_MAX) ? static_cast<int>(n) : INT_MAX; }

double number(lua_State* L, int index, const char* what);
std::int64_t integer(lua_State* L, int index, const char* what);
std::string string(lua_State* L, int index, const char* what);
// A file path: a string that is not empty (an empty one would name no file in the message).
std::string path(lua_State* L, int index, const char* what);
Vec3 vec3(lua_State* L, int index, const char* what);
Names string_list(lua_State* L, int index, const char* what);
// {{x, y, z}, ...}
Points point_list(lua_State* L, int index, const char* what);
// A Lua value converted to a parameter value (number, integer, boolean, string, {x,y,z},
// {"name", ...}, {{x,y,z}, ...}, a function (which the schema makes what the parameter
// takes), pbf.keyframes as a motion).
ParamValue param_value(lua_State* L, int index, const std::string& name);
// The key/value pairs of the table at `index` (absent or nil: none), sorted by key.
GivenParams table_params(lua_State* L, int index, const char* what);

template <int (*F)(lua_State*)>
int guarded(lua_State* L) {
  {
    std::string message;
    try {
      return F(L);
    } catch (const MissingFile& e) {
      message = where(L) + e.what() + beside_script(L, e.path());
    } catch (const Error& e) {
      message = e.located() ? e.what() : where(L) + e.what();
    } catch (const std::bad_alloc&) {
      message = where(L) + "out of memory";
    } catch (const std::exception& e) {
      message = where(L) + e.what();
    }
    lua_pushlstring(L, message.data(), message.size());
  }  // `message` is destroyed before lua_error jumps
  mark_engine_error(L);
  return lua_error(L);
}

}  // namespace pbf::lua
