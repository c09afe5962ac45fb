#pragma once
// Lua functions given as parameter values (a solid's motion, an emitter's speed or velocity),
// held for the engine, which calls them without knowing Lua.
#include <lua.hpp>
#include <memory>
#include <string>

#include "engine/registry/params.hpp"

namespace pbf::lua {

// A function kept in the registry while a holder keeps this. A holder may outlive the
// script's Lua state (an error ends the script before the simulation is destroyed): the
// state's own garbage collection clears a flag, after which `push` refuses and the
// destructor leaves the registry alone.
class FunctionRef {
 public:
  FunctionRef(lua_State* L, int index);
  ~FunctionRef();
  FunctionRef(const FunctionRef&) = delete;
  FunctionRef& operator=(const FunctionRef&) = delete;
  // Pushes the function and returns the state to call it in; throws Error once the state
  // has closed.
  lua_State* push() const;
  // "FILE:LINE" where the function is defined.
  const std::string& where() const { return where_; }

 private:
  lua_State* L_;
  std::shared_ptr<bool> alive_;
  int ref_;
  std::string where_;
};

// The function at `index` as a parameter value; the schema makes it a motion or a function
// of time and place (engine/registry/params.hpp, ScriptFunction).
ScriptFunctionPtr script_function(lua_State* L, int index);

}  // namespace pbf::lua
