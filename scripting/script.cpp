// The `pbf` table: each function reads its arguments with typed readers, calls the engine,
// and pushes plain Lua values back. Engine errors become one Lua error "FILE:LINE: message".
#include "scripting/script.hpp"

#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include "engine/distributed/comm.hpp"
#include "engine/core/names.hpp"
#include "engine/core/scene_commands.hpp"
#include "engine/core/simulation.hpp"
#include "engine/registry/style_registry.hpp"
#include "scripting/log_file.hpp"
#include "scripting/lua_callback.hpp"
#include "scripting/lua_motion.hpp"
#include "scripting/script_state.hpp"

namespace pbf {

namespace {

using lua::state;
using lua::table_arg;
using State = Script::State;

// Hands the script to lua_load one line at a time, so that the line the parser was reading
// is known when it fails without naming one. Prepares the text as luaL_loadfile does: a
// UTF-8 byte-order mark is dropped, and a first line starting with '#' (a Unix "#!" line)
// is emptied, its newline kept so that line numbers stay right.
class ScriptReader {
 public:
  explicit ScriptReader(std::string text) : text_(std::move(text)) {
    if (text_.rfind("\xEF\xBB\xBF", 0) == 0) text_.erase(0, 3);
    if (!text_.empty() && text_[0] == '#') text_.erase(0, std::min(text_.find('\n'), text_.size()));
  }
  static const char* read(lua_State*, void* data, std::size_t* size) {
    auto& r = *static_cast<ScriptReader*>(data);
    if (r.pos_ >= r.text_.size()) {
      *size = 0;
      return nullptr;
    }
    const std::size_t newline = r.text_.find('\n', r.pos_);
    const std::size_t end = newline == std::string::npos ? r.text_.size() : newline + 1;
    const char* line = r.text_.data() + r.pos_;
    *size = end - r.pos_;
    r.pos_ = end;
    ++r.line_;
    return line;
  }
  int line() const { return std::max(line_, 1); }

 private:
  std::string text_;
  std::size_t pos_ = 0;
  int line_ = 0;
};

int l_fix(lua_State* L) {
  State& S = state(L);
  S.not_running("pbf.fix");
  const std::string id = lua::string(L, 1, "pbf.fix: the id");
  const std::string style = lua::string(L, 2, "pbf.fix: the style");
  const std::string what = fmt::format("fix '{}' ({})", id, style);
  S.sim.add_fix(StyleRegistry::builtin().make_fix(id, style, lua::table_params(L, 3, what.c_str())));
  return 0;
}

int l_unfix(lua_State* L) {
  State& S = state(L);
  S.not_running("pbf.unfix");
  S.sim.remove_fix(lua::string(L, 1, "pbf.unfix: the id"));
  return 0;
}

int l_compute(lua_State* L) {
  State& S = state(L);
  S.not_running("pbf.compute");
  const std::string id = lua::string(L, 1, "pbf.compute: the id");
  const std::string style = lua::string(L, 2, "pbf.compute: the style");
  const std::string what = fmt::format("compute '{}' ({})", id, style);
  S.sim.add_compute(StyleRegistry::builtin().make_compute(id, style, lua::table_params(L, 3, what.c_str())));
  return 0;
}

int l_uncompute(lua_State* L) {
  State& S = state(L);
  S.not_running("pbf.uncompute");
  S.sim.remove_compute(lua::string(L, 1, "pbf.uncompute: the id"));
  return 0;
}

int l_value(lua_State* L) {
  State& S = state(L);
  const std::string id = lua::string(L, 1, "pbf.value: the compute id");
  Compute* c = &compute_to_evaluate(S.sim, id, "pbf.value");
  std::vector<double> v;
  if (c->per_particle()) {  // the value of the particle with id k at key k + 1 (gaps: removed particles)
    std::vector<std::int64_t> ids;
    c->evaluate_per_particle(S.sim, ids, v);
    lua_createtable(L, lua::size_hint(v.size()), 0);
    for (std::size_t i = 0; i < v.size(); ++i) {
      lua_pushnumber(L, v[i]);
      lua_rawseti(L, -2, static_cast<lua_Integer>(ids[i] + 1));
    }
    return 1;
  }
  c->evaluate(S.sim, v);
  const auto names = c->names();
  if (names.size() == 1) {
    lua_pushnumber(L, v.at(0));
    return 1;
  }
  lua_createtable(L, 0, lua::size_hint(names.size()));
  for (std::size_t k = 0; k < names.size(); ++k) {
    lua_pushnumber(L, v.at(k));
    lua_setfield(L, -2, names[k].c_str());
  }
  return 1;
}

int l_thermo(lua_State* L) {
  State& S = state(L);
  S.not_running("pbf.thermo");
  if (lua_type(L, 1) != LUA_TTABLE) throw Error("pbf.thermo takes a table {every = K, columns = {...}, csv = PATH}");
  std::int64_t every = 100;
  std::vector<std::string> columns = {"step", "time"};
  std::string csv;
  const std::vector<std::string> keys = {"every", "columns", "csv"};
  lua_pushnil(L);
  while (lua_next(L, 1)) {
    if (lua_type(L, -2) != LUA_TSTRING)
      throw Error(fmt::format("pbf.thermo: every key must be a name (every, columns or csv), got a {}",
                              luaL_typename(L, -2)));
    const std::string key = lua_tostring(L, -2);
    if (key == "every") every = lua::integer(L, -1, "pbf.thermo: 'every'");
    else if (key == "csv") csv = lua::string(L, -1, "pbf.thermo: 'csv'");
    else if (key == "columns") {
      if (lua_type(L, -1) != LUA_TTABLE) throw Error("pbf.thermo: 'columns' must be a list of names");
      columns.clear();
      const lua_Unsigned n = lua_rawlen(L, -1);
      for (lua_Unsigned k = 1; k <= n; ++k) {
        lua_rawgeti(L, -1, static_cast<lua_Integer>(k));  // k <= a table's length fits
        columns.push_back(lua::string(L, -1, "pbf.thermo: a column"));
        lua_pop(L, 1);
      }
    } else {
      throw Error(fmt::format("pbf.thermo: unknown key '{}'{}; valid keys: {}", key, did_you_mean(key, keys),
                              fmt::join(keys, ", ")));
    }
    lua_pop(L, 1);
  }
  // Range-checked here, as the conversion to int below would wrap a large negative count.
  if (every < 0) throw Error(fmt::format("thermo: 'every' must be >= 0, got {}", every));
  if (every > 1000000000) throw Error("pbf.thermo: 'every' is too large");
  S.sim.thermo().configure(S.sim, static_cast<int>(every), columns, csv);
  return 0;
}

int l_every(lua_State* L) {
  State& S = state(L);
  S.not_running("pbf.every");
  const std::string id = lua::string(L, 1, "pbf.every: the id");
  const std::int64_t every = lua::integer(L, 2, "pbf.every: the interval in steps");
  if (lua_type(L, 3) != LUA_TFUNCTION) throw Error("pbf.every: the third argument must be a function");
  lua_pushvalue(L, 3);
  S.sim.add_fix(lua::make_callback_fix(L, id, every));
  return 0;
}

// A run from the script: callbacks may not change the pipeline meanwhile, and Ctrl-C ends
// the script even when a pcall catches the error it raises.
template <class F>
void guarded_run(State& S, F&& run) {
  if (S.interrupted) throw *S.interrupted;
  lua::check_variables_at_first_run(S);
  struct Running {
    bool& flag;
    ~Running() { flag = false; }
  } guard{S.running};
  S.running = true;
  try {
    run();
  } catch (const Interrupted& e) {
    S.interrupted = e;  // passes through Lua as an error, then ends the script as itself
    throw;
  }
}

int l_run(lua_State* L) {
  State& S = state(L);
  S.not_running("pbf.run");
  const std::int64_t steps = lua::integer(L, 1, "pbf.run: the number of steps");
  guarded_run(S, [&] { S.sim.run(steps); });
  return 0;
}

int l_run_until(lua_State* L) {
  State& S = state(L);
  S.not_running("pbf.run_until");
  const double time = lua::number(L, 1, "pbf.run_until: the end time (s)");
  guarded_run(S, [&] { S.sim.run_until(time); });
  return 0;
}

int l_step(lua_State* L) {
  lua_pushinteger(L, static_cast<lua_Integer>(state(L).sim.step()));
  return 1;
}
int l_time(lua_State* L) {
  lua_pushnumber(L, state(L).sim.time());
  return 1;
}
int l_count(lua_State* L) {  // every rank's particles
  lua_pushinteger(L, static_cast<lua_Integer>(state(L).sim.particles().global_size()));
  return 1;
}
int l_rank_count(lua_State* L) {  // this rank's own (where a distributed run put them)
  lua_pushinteger(L, static_cast<lua_Integer>(state(L).sim.particles().size()));
  return 1;
}
int l_rank(lua_State* L) {
  lua_pushinteger(L, comm::rank());
  return 1;
}
int l_ranks(lua_State* L) {
  lua_pushinteger(L, comm::ranks());
  return 1;
}

int l_timing(lua_State* L) {
  const TimingTable& t = state(L).sim.last_timing();
  lua_createtable(L, 0, 4);
  lua_pushnumber(L, t.wall_seconds);
  lua_setfield(L, -2, "wall");
  lua_pushnumber(L, t.wall_seconds > 0 ? double(t.steps) * double(t.particles) / t.wall_seconds : 0.0);
  lua_setfield(L, -2, "particle_steps_per_second");
  lua_createtable(L, lua::size_hint(t.rows().size()), 0);
  for (std::size_t r = 0; r < t.rows().size(); ++r) {
    lua_createtable(L, 0, 3);
    lua_pushstring(L, t.rows()[r].stage.c_str());
    lua_setfield(L, -2, "stage");
    lua_pushstring(L, t.rows()[r].label.c_str());
    lua_setfield(L, -2, "label");
    lua_pushnumber(L, t.rows()[r].seconds);
    lua_setfield(L, -2, "seconds");
    lua_rawseti(L, -2, static_cast<lua_Integer>(r + 1));
  }
  lua_setfield(L, -2, "rows");
  return 1;
}

// Lua's print, also copied into the log file; in a distributed run, rank 0's only (every rank
// runs the script). pbf.print_all prints on every rank, naming it.
int print_line(lua_State* L, bool every_rank) {
  if (!every_rank && !comm::root()) return 0;
  const int n = lua_gettop(L);
  luaL_Buffer line;
  luaL_buffinit(L, &line);
  for (int i = 1; i <= n; ++i) {
    if (i > 1) luaL_addchar(&line, '\t');
    luaL_tolstring(L, i, nullptr);  // __tostring and __name as Lua's print
    luaL_addvalue(&line);
  }
  luaL_addchar(&line, '\n');
  luaL_pushresult(&line);
  if (every_rank && comm::distributed()) {
    lua_pushfstring(L, "rank %d: %s", comm::rank(), lua_tostring(L, -1));
    lua_remove(L, -2);
  }
  std::size_t size = 0;
  const char* text = lua_tolstring(L, -1, &size);
  log_file::console({text, size}, false);  // in order with the info lines, which spdlog flushes
  log_file::write({text, size});
  return 0;
}
int l_print(lua_State* L) { return print_line(L, false); }
int l_print_all(lua_State* L) { return print_line(L, true); }

// Ctrl-C in Lua code (Script::set_interruptible): the signal handler may only set a hook,
// which raises the error at the next instruction, as lua.c's does.
lua_State* interruptible_state = nullptr;

void interrupt_hook(lua_State* L, lua_Debug*) {
  lua_sethook(L, nullptr, 0, 0);
  luaL_error(L, "interrupted (Ctrl-C)");
}

extern "C" void on_lua_interrupt(int) {
  if (interruptible_state)
    lua_sethook(interruptible_state, interrupt_hook, LUA_MASKCALL | LUA_MASKRET | LUA_MASKCOUNT, 1);
}

// SIGINT stops Lua code while one exists; the action before comes back after.
class LuaInterrupt {
 public:
  LuaInterrupt(lua_State* L, bool on) : L_(L), on_(on) {
    if (!on_) return;
    interruptible_state = L;
    struct sigaction action = {};
    action.sa_handler = on_lua_interrupt;
    sigemptyset(&action.sa_mask);
    sigaction(SIGINT, &action, &previous_);
  }
  ~LuaInterrupt() {
    if (!on_) return;
    sigaction(SIGINT, &previous_, nullptr);
    interruptible_state = nullptr;
    lua_sethook(L_, nullptr, 0, 0);  // one the signal set that the code ended before meeting
  }

 private:
  lua_State* L_;
  bool on_;
  struct sigaction previous_ = {};
};

}  // namespace

Script::Script(Simulation& sim) : state_(new State(sim)) {
  lua_State* L = luaL_newstate();
  if (!L) throw Error("cannot create a Lua state (out of memory)");
  state_->L = L;
  luaL_openlibs(L);
  lua_pushcfunction(L, l_print);
  lua_setglobal(L, "print");
  std::vector<luaL_Reg> functions = lua::scene_functions();
  const luaL_Reg pipeline[] = {
      {"fix", lua::guarded<l_fix>},
      {"unfix", lua::guarded<l_unfix>},
      {"compute", lua::guarded<l_compute>},
      {"uncompute", lua::guarded<l_uncompute>},
      {"value", lua::guarded<l_value>},
      {"thermo", lua::guarded<l_thermo>},
      {"every", lua::guarded<l_every>},
      {"keyframes", lua::guarded<lua::l_keyframes>},
      {"run", lua::guarded<l_run>},
      {"run_until", lua::guarded<l_run_until>},
      {"step", lua::guarded<l_step>},
      {"time", lua::guarded<l_time>},
      {"count", lua::guarded<l_count>},
      {"rank", lua::guarded<l_rank>},
      {"rank_count", lua::guarded<l_rank_count>},
      {"ranks", lua::guarded<l_ranks>},
      {"print_all", lua::guarded<l_print_all>},
      {"timing", lua::guarded<l_timing>}};
  functions.insert(functions.end(), std::begin(pipeline), std::end(pipeline));
  functions.push_back({nullptr, nullptr});
  lua_newtable(L);
  lua_pushlightuserdata(L, state_.get());
  luaL_setfuncs(L, functions.data(), 1);
  lua_pushstring(L, PBF_VERSION);
  lua_setfield(L, -2, "version");
  lua_setglobal(L, "pbf");
  set_variables({});
}

Script::~Script() {
  // Scripted fixes hold references into this Lua state: they go before it closes.
  std::vector<std::string> scripted;
  for (const auto& f : state_->sim.fixes())
    if (f->style() == "lua") scripted.push_back(f->id());
  for (const auto& id : scripted) state_->sim.remove_fix(id);
  lua_close(state_->L);
}

void Script::set_variables(const std::vector<std::pair<std::string, std::string>>& variables) {
  lua::install_variables(state_->L, *state_, variables);
}

void Script::run_file(const std::string& path) {
  state_->script_path = path;
  if (!std::filesystem::is_regular_file(path)) throw Error(fmt::format("{}: cannot open the script", path), true);
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in) throw Error(fmt::format("{}: cannot read the script", path), true);
  run_chunk(text.str(), path);
}

void Script::run_text(const std::string& text, const std::string& name) {
  state_->script_path = name;
  run_chunk(text, name);
}

// Lua shortens long chunk names in its messages; the short form is found to put the path back.
void Script::run_chunk(const std::string& text, const std::string& path) {
  lua_State* L = state_->L;
  const std::string chunk = "@" + path;
  lua_Debug ar;
  luaL_loadbuffer(L, "return", 6, chunk.c_str());
  lua_getinfo(L, ">S", &ar);  // (pops the function)
  const std::string short_src = ar.short_src;
  auto full_path = [&](std::string message) {
    if (short_src != path && message.rfind(short_src + ":", 0) == 0) message = path + message.substr(short_src.size());
    return message;
  };
  ScriptReader reader(text);
  LuaInterrupt interrupt(L, interruptible_);
  if (lua_load(L, ScriptReader::read, &reader, chunk.c_str(), "t") != LUA_OK) {
    std::string message = lua_tostring(L, -1);  // load errors are strings
    lua_pop(L, 1);
    // The parser's C stack overflow (expressions, tables or calls nested too deeply) comes
    // without a line: it is the line the parser was reading.
    if (!lua::has_position(message.c_str()))
      message = fmt::format("{}:{}: {}{}", path, reader.line(), message,
                            message == "C stack overflow" ? " (nested too deeply)" : "");
    throw Error(full_path(message), true);
  }
  const int status = lua::pcall(L, 0, 0);
  if (status != LUA_OK) {
    std::string message = lua::pop_error(L);
    if (state_->interrupted) throw *state_->interrupted;
    // Out of memory and errors in the message handler, where Lua calls no handler, come
    // without a place: the script's.
    if (status == LUA_ERRMEM || status == LUA_ERRERR) message = path + ": " + message;
    throw Error(full_path(message), true);
  }
  if (state_->interrupted) throw *state_->interrupted;  // caught by a pcall in the script
}

std::vector<std::string> Script::unread_variable_warnings() {
  return lua::report_unread_variables(*state_, "was never read", "", false);
}

bool Script::reads_variable(const std::string& name) const { return state_->variables_looked_up.count(name) > 0; }

}  // namespace pbf
