// The `var` table: the command line's -v NAME=VALUE pairs. Reads go through __index, so
// the engine knows which variables the script read (given or not). A given one it has not
// read when the first run starts, close to a name it did read, is a typo: reported then, with
// that name; any other still unread when the script ends, then.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "engine/core/names.hpp"
#include "scripting/script_state.hpp"

namespace pbf::lua {

namespace {

int l_var_index(lua_State* L) {
  State& S = state(L);
  if (lua_type(L, 2) == LUA_TSTRING) {
    const std::string name = lua_tostring(L, 2);
    S.variables_looked_up.insert(name);
    auto it = S.variable_read.find(name);
    if (it != S.variable_read.end()) it->second = true;
  }
  lua_pushvalue(L, 2);
  lua_rawget(L, lua_upvalueindex(2));
  return 1;
}

int l_var_pairs(lua_State* L) {
  for (auto& entry : state(L).variable_read) entry.second = true;
  lua_getglobal(L, "next");
  lua_pushvalue(L, lua_upvalueindex(2));
  lua_pushnil(L);
  return 3;
}

}  // namespace

void install_variables(lua_State* L, State& S, const std::vector<std::pair<std::string, std::string>>& variables) {
  S.variable_read.clear();
  S.variables_looked_up.clear();
  S.unread_reported.clear();
  lua_newtable(L);  // the values
  for (const auto& [name, text] : variables) {
    if (lua_stringtonumber(L, text.c_str()) == 0) lua_pushstring(L, text.c_str());  // integers stay integers
    lua_setfield(L, -2, name.c_str());
    S.variable_read[name] = false;
  }
  const int values = lua_gettop(L);
  lua_newtable(L);           // var: an empty proxy
  lua_createtable(L, 0, 3);  // its metatable
  lua_pushlightuserdata(L, &S);
  lua_pushvalue(L, values);
  lua_pushcclosure(L, l_var_index, 2);
  lua_setfield(L, -2, "__index");
  lua_pushlightuserdata(L, &S);
  lua_pushvalue(L, values);
  lua_pushcclosure(L, l_var_pairs, 2);
  lua_setfield(L, -2, "__pairs");
  lua_pushvalue(L, values);
  lua_setfield(L, -2, "__newindex");
  lua_setmetatable(L, -2);
  lua_setglobal(L, "var");
  lua_pop(L, 1);
}

std::vector<std::string> report_unread_variables(State& S, const char* verb, const char* when, bool typos_only) {
  const std::vector<std::string> read(S.variables_looked_up.begin(), S.variables_looked_up.end());
  std::vector<std::string> messages;
  for (const auto& [name, was_read] : S.variable_read) {
    if (was_read || S.unread_reported.count(name) || (typos_only && nearest_name(name, read).empty())) continue;
    S.unread_reported.insert(name);
    messages.push_back(fmt::format("variable '{}' given with -v {} by {}{}{}", name, verb, S.script_path, when,
                                   did_you_mean(name, read)));
  }
  return messages;
}

void check_variables_at_first_run(State& S) {
  if (S.variables_checked) return;
  S.variables_checked = true;
  // A continuation the script cannot make would start again from t = 0 and write over the
  // outputs of the run it was asked to continue.
  const auto restart = S.variable_read.find("restart");
  if (restart != S.variable_read.end() && !restart->second)
    throw Error(fmt::format("-v restart was given, but {} has not read var.restart before its first run: the run "
                            "would start again from t = 0 and write over the outputs of the run it was to "
                            "continue; build the scene with pbf.scene, which reads it "
                            "(docs/user-guide.md#continuing-a-run-exactly)",
                            S.script_path));
  // Only those that look like a typo of a variable the script read: another may still be read
  // after a run (a name for the file the script writes at the end); the script's end tells.
  for (const std::string& message : report_unread_variables(S, "has not been read", " before its first run", true))
    spdlog::warn("{}", message);
}

}  // namespace pbf::lua
