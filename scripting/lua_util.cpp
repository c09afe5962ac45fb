#include "scripting/lua_util.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fmt/format.h>

#include "scripting/lua_function.hpp"
#include "scripting/lua_motion.hpp"

namespace pbf::lua {

namespace {

// The innermost Lua function on the stack below the running C function (C functions have
// no line).
bool innermost_lua_frame(lua_State* L, lua_Debug& ar) {
  for (int level = 1; lua_getstack(L, level, &ar); ++level) {
    lua_getinfo(L, "Sl", &ar);
    if (ar.currentline > 0) return true;
  }
  return false;
}

// A file chunk's source is "@PATH": the path as given, which short_src may abbreviate.
const char* chunk_path(const lua_Debug& ar) { return ar.source[0] == '@' ? ar.source + 1 : ar.short_src; }

const char engine_error_key = 0;  // its address keys the engine's last message in the registry

int to_string(lua_State* L) {
  luaL_tolstring(L, 1, nullptr);
  return 1;
}

// The message handler of `pcall`. It runs on the erring stack, before it unwinds, so the
// frames of the error are still there to be found. Only Lua API calls: a longjmp must not
// cross C++ objects.
int message_handler(lua_State* L) {
  lua_rawgetp(L, LUA_REGISTRYINDEX, &engine_error_key);
  const bool engine = lua_type(L, 1) == LUA_TSTRING && lua_rawequal(L, 1, -1);
  lua_pop(L, 1);
  if (engine) return 1;
  if (lua_type(L, 1) == LUA_TSTRING) {
    if (has_position(lua_tostring(L, 1))) return 1;
    lua_pushvalue(L, 1);
  } else {
    // Numbers and objects with __tostring have a text; the conversion is protected, as a
    // failing __tostring would otherwise replace the error with "error in error handling".
    bool text = lua_type(L, 1) == LUA_TNUMBER;
    if (luaL_getmetafield(L, 1, "__tostring") != LUA_TNIL) {
      lua_pop(L, 1);
      text = true;
    }
    if (text) {
      lua_pushcfunction(L, to_string);
      lua_pushvalue(L, 1);
      if (lua_pcall(L, 1, 1, 0) != LUA_OK) {
        lua_pop(L, 1);
        text = false;
      }
    }
    if (!text) lua_pushfstring(L, "(error object is a %s value)", luaL_typename(L, 1));
  }
  lua_Debug ar;
  if (innermost_lua_frame(L, ar)) {
    lua_pushfstring(L, "%s:%d: ", chunk_path(ar), ar.currentline);
    lua_insert(L, -2);
    lua_concat(L, 2);
  }
  return 1;
}

}  // namespace

bool has_position(const char* message) {
  for (const char* p = message; *p && *p != '\n'; ++p) {
    if (*p != ':' || !std::isdigit(static_cast<unsigned char>(p[1]))) continue;
    const char* q = p + 1;
    while (std::isdigit(static_cast<unsigned char>(*q))) ++q;
    if (*q == ':') return true;
  }
  return false;
}

std::string where(lua_State* L) {
  // The innermost Lua function on the stack: the script line that called into the engine.
  lua_Debug ar;
  if (!innermost_lua_frame(L, ar)) return "";
  return fmt::format("{}:{}: ", chunk_path(ar), ar.currentline);
}

std::string beside_script(lua_State* L, const std::string& path) {
  namespace fs = std::filesystem;
  lua_Debug ar;
  if (fs::path(path).is_absolute() || !innermost_lua_frame(L, ar) || ar.source[0] != '@') return "";
  std::error_code ec;
  const fs::path here = fs::current_path(ec);
  const fs::path folder = fs::weakly_canonical(fs::absolute(chunk_path(ar), ec).parent_path(), ec);
  if (ec || folder == here) return "";
  std::string note = fmt::format("; the script is in {}", folder.string());
  const fs::path beside = folder / path;
  if (fs::exists(beside, ec)) {
    std::string from_here = fs::relative(beside, here, ec).string();
    if (ec || from_here.empty() || from_here.size() > beside.string().size()) from_here = beside.string();
    note += fmt::format(", which holds '{}': give its path from the current folder, '{}'", path, from_here);
  }
  return note;
}

void mark_engine_error(lua_State* L) {
  lua_pushvalue(L, -1);
  lua_rawsetp(L, LUA_REGISTRYINDEX, &engine_error_key);
}

int pcall(lua_State* L, int nargs, int nresults) {
  const int function = lua_gettop(L) - nargs;
  lua_pushcfunction(L, message_handler);
  lua_insert(L, function);  // below the function
  const int status = lua_pcall(L, nargs, nresults, function);
  lua_remove(L, function);
  return status;
}

std::string pop_error(lua_State* L) {
  std::string message = lua_type(L, -1) == LUA_TSTRING ? lua_tostring(L, -1) : "(error object is not a string)";
  lua_pop(L, 1);
  return message;
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
  // Converting a float that is not finite, or outside [-2^63, 2^63), to an integer is
  // undefined behaviour: check first. (0/0 is "-nan" on x86; its sign means nothing.)
  if (!std::isfinite(v) || v != std::floor(v) || v < -0x1p63 || v >= 0x1p63) {
    const std::string given = std::isnan(v) ? "nan" : fmt::format("{}", v);
    throw Error(fmt::format("{} must be an integer, got {}", what, given));
  }
  return static_cast<std::int64_t>(v);
}

std::string string(lua_State* L, int index, const char* what) {
  if (lua_type(L, index) != LUA_TSTRING)
    throw Error(fmt::format("{} must be a string, got {}", what, luaL_typename(L, index)));
  std::size_t len = 0;
  const char* s = lua_tolstring(L, index, &len);
  // A Lua string may hold zero bytes; a path or a name that did would be cut short at the
  // first one by the C functions that take it.
  if (std::char_traits<char>::find(s, len, '\0'))
    throw Error(fmt::format("{} must not contain a zero byte ('\\0')", what));
  return std::string(s, len);
}

std::string path(lua_State* L, int index, const char* what) {
  std::string p = string(L, index, what);
  if (p.empty()) throw Error(fmt::format("{} must not be empty", what));
  return p;
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

Points point_list(lua_State* L, int index, const char* what) {
  index = lua_absindex(L, index);
  Points points;
  const auto n = static_cast<lua_Integer>(lua_rawlen(L, index));
  for (lua_Integer k = 1; k <= n; ++k) {
    lua_rawgeti(L, index, k);
    try {
      points.push_back(vec3(L, -1, fmt::format("{}: point {}", what, k).c_str()));
    } catch (...) {
      lua_pop(L, 1);
      throw;
    }
    lua_pop(L, 1);
  }
  return points;
}

ParamValue param_value(lua_State* L, int index, const std::string& name) {
  switch (lua_type(L, index)) {
    case LUA_TNUMBER:
      if (lua_isinteger(L, index)) return static_cast<std::int64_t>(lua_tointeger(L, index));
      return static_cast<double>(lua_tonumber(L, index));
    case LUA_TBOOLEAN: return lua_toboolean(L, index) != 0;
    case LUA_TSTRING: return string(L, index, fmt::format("parameter '{}'", name).c_str());
    case LUA_TFUNCTION: return script_function(L, index);
    case LUA_TUSERDATA:
      if (MotionPtr motion = motion_value(L, index)) return motion;
      throw Error(fmt::format("parameter '{}': this userdata is no parameter value", name));
    case LUA_TTABLE: {
      lua_rawgeti(L, index, 1);
      const int first = lua_type(L, -1);
      lua_pop(L, 1);
      if (first == LUA_TSTRING || first == LUA_TNIL)  // {} is no names
        return string_list(L, index, fmt::format("parameter '{}'", name).c_str());
      if (first == LUA_TTABLE) return point_list(L, index, fmt::format("parameter '{}'", name).c_str());
      // The binding does not know the parameter's type: a table that is no {x, y, z} is
      // told both of what a table can be (the schema then says which one it wanted).
      if (lua_rawlen(L, index) == 2) {  // a pair of lengths
        Vec2 v;
        for (int k = 0; k < 2; ++k) {
          lua_rawgeti(L, index, k + 1);
          const bool ok = lua_type(L, -1) == LUA_TNUMBER;
          v[static_cast<std::size_t>(k)] = lua_tonumber(L, -1);
          lua_pop(L, 1);
          if (!ok) throw Error(fmt::format("parameter '{}' must be a pair of numbers {{a, b}}", name));
        }
        return v;
      }
      if (lua_rawlen(L, index) != 3)
        throw Error(fmt::format("parameter '{}' must be a vector {{x, y, z}} or a list of names {{\"a\", \"b\"}}, got a "
                                "table of {} numbers",
                                name, lua_rawlen(L, index)));
      return vec3(L, index, fmt::format("parameter '{}'", name).c_str());
    }
    default:
      throw Error(fmt::format("parameter '{}': a {} is not a parameter value (number, boolean, string, "
                              "{{x, y, z}}, {{\"name\", ...}}, {{{{x, y, z}}, ...}}, a function or a motion)",
                              name, luaL_typename(L, index)));
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
