#include "scripting/lua_util.hpp"

#include <algorithm>
#include <fmt/format.h>

namespace pbf::lua {

std::string where(lua_State* L) {
  // The innermost Lua function on the stack: the script line that called into the engine.
  lua_Debug ar;
  for (int level = 1; lua_getstack(L, level, &ar); ++level) {
    lua_getinfo(L, "Sl", &ar);
    if (ar.currentline <= 0) continue;  // a C function
    // A file chunk's source is "@PATH": the path as given, which short_src may abbreviate.
    return fmt::format("{}:{}: ", ar.source[0] == '@' ? ar.source + 1 : ar.short_src, ar.currentline);
  }
  return "";
}

double number(lua_State* L, int index, const char* what) {
  int ok = 0;
  const lua_Number v = lua_tonumberx(L, index, &ok);
  if (!ok || lua_type(L, index) != LUA_TNUMBER)
    throw Error(fmt::format("{} must be a number, got {}", what, luaL_typename(L, index)));
  return v;
}

std::int64_t integer(lua_State* L, int index, const char* what) {
  const double v = number(L, index, what);
  if (lua_isinteger(L, index)) return lua_tointeger(L, index);
  if (v != static_cast<double>(static_cast<std::int64_t>(v)))
    throw Error(fmt::format("{} must be an integer, got {}", what, v));
  return static_cast<std::int64_t>(v);
}

std::string string(lua_State* L, int index, const char* what) {
  if (lua_type(L, index) != LUA_TSTRING)
    throw Error(fmt::format("{} must be a string, got {}", what, luaL_typename(L, index)));
  std::size_t len = 0;
  const char* s = lua_tolstring(L, index, &len);
  return std::string(s, len);
}

Vec3 vec3(lua_State* L, int index, const char* what) {
  index = lua_absindex(L, index);
  if (lua_type(L, index) != LUA_TTABLE || lua_rawlen(L, index) != 3)
    throw Error(fmt::format("{} must be a vector {{x, y, z}}", what));
  Vec3 v;
  for (int k = 0; k < 3; ++k) {
    lua_rawgeti(L, index, k + 1);
    const bool ok = lua_type(L, -1) == LUA_TNUMBER;
    v[k] = lua_tonumber(L, -1);
    lua_pop(L, 1);
    if (!ok) throw Error(fmt::format("{} must be a vector of three numbers", what));
  }
  return v;
}

Names string_list(lua_State* L, int index, const char* what) {
  index = lua_absindex(L, index);
  Names names;
  const auto n = static_cast<lua_Integer>(lua_rawlen(L, index));
  for (lua_Integer k = 1; k <= n; ++k) {
    lua_rawgeti(L, index, k);
    const bool ok = lua_type(L, -1) == LUA_TSTRING;
    if (ok) names.emplace_back(lua_tostring(L, -1));
    lua_pop(L, 1);
    if (!ok) throw Error(fmt::format("{} must be a list of names (strings)", what));
  }
  return names;
}

ParamValue param_value(lua_State* L, int index, const std::string& name) {
  switch (lua_type(L, index)) {
    case LUA_TNUMBER:
      if (lua_isinteger(L, index)) return static_cast<std::int64_t>(lua_tointeger(L, index));
      return static_cast<double>(lua_tonumber(L, index));
    case LUA_TBOOLEAN: return lua_toboolean(L, index) != 0;
    case LUA_TSTRING: return string(L, index, name.c_str());
    case LUA_TTABLE: {
      lua_rawgeti(L, index, 1);
      const bool names = lua_type(L, -1) == LUA_TSTRING || lua_type(L, -1) == LUA_TNIL;  // {} is no names
      lua_pop(L, 1);
      if (names) return string_list(L, index, fmt::format("parameter '{}'", name).c_str());
      return vec3(L, index, fmt::format("parameter '{}'", name).c_str());
    }
    default:
      throw Error(fmt::format("parameter '{}': a {} is not a parameter value (number, boolean, string or "
                              "{{x, y, z}} or {{\"name\", ...}})", name, luaL_typename(L, index)));
  }
}

GivenParams table_params(lua_State* L, int index, const char* what) {
  GivenParams given;
  if (lua_isnoneornil(L, index)) return given;
  if (lua_type(L, index) != LUA_TTABLE)
    throw Error(fmt::format("{} must be a table of name = value, got {}", what, luaL_typename(L, index)));
  index = lua_absindex(L, index);
  lua_pushnil(L);
  while (lua_next(L, index)) {
    if (lua_type(L, -2) != LUA_TSTRING) {
      lua_pop(L, 2);
      throw Error(fmt::format("{}: every key must be a parameter name (a string)", what));
    }
    const std::string name = lua_tostring(L, -2);
    try {
      given.emplace_back(name, param_value(L, -1, name));
    } catch (const Error& e) {
      lua_pop(L, 2);
      throw Error(fmt::format("{}: {}", what, e.what()));
    }
    lua_pop(L, 1);
  }
  std::sort(given.begin(), given.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  return given;
}

}  // namespace pbf::lua
