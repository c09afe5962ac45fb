#pragma once
// A value that may vary in time and space, f(t, x): a number or a vector, given by a script as
// a constant or as a Lua function of the time and a point (an emitter's inflow speed or
// velocity over its opening). The Lua functions are wrapped in scripting/lua_function.cpp, so
// the engine calls them without knowing Lua. A Lua state belongs to one thread, so a caller
// calls `at` from serial code only, never inside a parallel loop; and, as a function may keep
// state of its own, with the same arguments in the same order on every rank.
#include <fmt/format.h>

#include <string>

#include "engine/registry/params.hpp"

namespace pbf {

class SpaceTimeFunction {
 public:
  virtual ~SpaceTimeFunction() = default;
  // The value at time t at the point x: a number in [0] (the others 0), or a vector. Throws
  // Error when it cannot be had: the script's function failed (a message that names the
  // script's line), or returned something other than the number or vector it must. Whether
  // the values make sense (finite, within a range) is the caller's to check: it knows what
  // they mean.
  virtual Vec3 at(double t, const Vec3& x) const = 0;
  // Whether the value is the same everywhere and always (a constant: nothing to call).
  virtual bool constant() const = 0;
  // One line for messages: the constant, or where the function is defined.
  virtual std::string description() const = 0;
};

// A number ({v, 0, 0}) or a vector the script gave as such.
class ConstantFunction final : public SpaceTimeFunction {
 public:
  ConstantFunction(const Vec3& value, int components) : value_(value), components_(components) {}
  Vec3 at(double, const Vec3&) const override { return value_; }
  bool constant() const override { return true; }
  std::string description() const override {
    if (components_ == 1) return fmt::format("{}", value_[0]);
    return fmt::format("{{{}, {}, {}}}", value_[0], value_[1], value_[2]);
  }

 private:
  Vec3 value_;
  int components_;
};

}  // namespace pbf
