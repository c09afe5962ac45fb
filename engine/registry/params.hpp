#pragma once
// Style parameters as data: each style declares a schema (name, type, default, unit, doc);
// values given by a script are checked against it before the style is constructed.
#include <array>
#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace pbf {

class Motion;             // engine/geometry/motion.hpp: a solid's pose as a function of time
class SpaceTimeFunction;  // engine/geometry/space_time_function.hpp: a value as a function of t and x

// RealFunction and Vector3Function: a number or a vector, or a function of time and place
// that gives one (an emitter's speed or velocity).
enum class ParamType {
  Real, Integer, Bool, String, Vector3, StringList, PointList, Motion, Vector2, RealFunction, Vector3Function
};
const char* type_name(ParamType type);

using Vec3 = std::array<double, 3>;
using Vec2 = std::array<double, 2>;  // two lengths (a rectangle's sides)
using Names = std::vector<std::string>;
using Points = std::vector<Vec3>;
using MotionPtr = std::shared_ptr<const Motion>;
using SpaceTimeFunctionPtr = std::shared_ptr<const SpaceTimeFunction>;

// A function a script gave as a parameter value. The binding cannot tell what a function is
// for (it does not know the parameter's type); the schema does, and the check of a value asks
// the function for what the parameter's type needs (scripting/lua_function.cpp makes them).
class ScriptFunction {
 public:
  virtual ~ScriptFunction() = default;
  // As a solid's motion: function(t) returning {translate = {x, y, z}, rotate = {rx, ry, rz}}.
  virtual MotionPtr motion() const = 0;
  // As a value of time and place: function(t, x, y, z) returning a number (components 1) or
  // a vector {a, b, c} (components 3).
  virtual SpaceTimeFunctionPtr of_time_and_place(int components) const = 0;
  // "defined at FILE:LINE", for messages.
  virtual std::string description() const = 0;
};
using ScriptFunctionPtr = std::shared_ptr<const ScriptFunction>;

using ParamValue = std::variant<double, std::int64_t, bool, std::string, Vec3, Names, Points, MotionPtr, Vec2,
                                ScriptFunctionPtr, SpaceTimeFunctionPtr>;

std::string format_value(const ParamValue& value);

// The values a number may take: checked with the type (for a vector, each component), shown
// by `pbfengine help`. An open end excludes its bound ("> 0" rather than ">= 0").
struct Range {
  double lo = -std::numeric_limits<double>::infinity(), hi = std::numeric_limits<double>::infinity();
  bool lo_open = false, hi_open = false;
  bool contains(double v) const { return (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi); }
  bool limited() const { return lo != -std::numeric_limits<double>::infinity() || hi != std::numeric_limits<double>::infinity(); }
  std::string text() const;  // "[0, 1]", "> 0", "(0, 1]", ...
};

struct ParamSpec {
  std::string name;
  ParamType type;
  std::optional<ParamValue> default_value;  // none: the parameter is required
  std::string unit;                         // "" for dimensionless
  std::string doc;                          // one line
  bool optional = false;                    // no default, and may be left out (Params::has)
  Range range{};                            // numbers outside are refused (default: any finite)
  std::vector<std::string> choices{};       // a string must be one of these (empty: any)
  bool one_number_for_all = false;          // a vector may be given as one number (a scale)

  // The range, written where the schema lists the parameter: {...}.within(0, 1).
  ParamSpec within(double lo, double hi) && { return with_range({lo, hi, false, false}); }
  ParamSpec at_least(double lo) && { return with_range({lo, Range{}.hi, false, false}); }
  ParamSpec above(double lo) && { return with_range({lo, Range{}.hi, true, false}); }
  ParamSpec above_within(double lo, double hi) && { return with_range({lo, hi, true, false}); }  // (lo, hi]
  ParamSpec magnitude_at_most(double most) && { return with_range({-most, most, false, false}); }
  // A vector that may be given as one number, standing for all three components (a scale;
  // not an acceleration, where 9.81 for {0, 0, -9.81} would be a slip).
  ParamSpec or_one_number() && {
    one_number_for_all = true;
    return std::move(*this);
  }
  ParamSpec one_of(std::vector<std::string> names) && {
    choices = std::move(names);
    return std::move(*this);
  }
  // The range or the choices, as `pbfengine help` shows them ("-" for none).
  std::string allowed() const;

 private:
  ParamSpec with_range(Range r) {
    range = r;
    return std::move(*this);
  }
};

// Values as the script gave them (numbers keep their Lua integer/float distinction).
using GivenParams = std::vector<std::pair<std::string, ParamValue>>;

// Checked values: every parameter of the schema is present with its declared type.
class Params {
 public:
  Params() = default;
  // Checks `given` against `schema`; errors name `what` (e.g. "fix 'walls' (box)").
  Params(const std::string& what, const std::vector<ParamSpec>& schema, const GivenParams& given);

  double real(const std::string& name) const;
  std::int64_t integer(const std::string& name) const;
  bool boolean(const std::string& name) const;
  const std::string& string(const std::string& name) const;
  Vec3 vec3(const std::string& name) const;
  Vec2 vec2(const std::string& name) const;
  const Names& names(const std::string& name) const;
  const Points& points(const std::string& name) const;
  MotionPtr motion(const std::string& name) const;
  // A RealFunction or Vector3Function parameter, a constant as a function too.
  SpaceTimeFunctionPtr function(const std::string& name) const;
  bool has(const std::string& name) const { return values_.count(name) > 0; }
  const std::map<std::string, ParamValue>& values() const { return values_; }

 private:
  const ParamValue& at(const std::string& name) const;
  std::map<std::string, ParamValue> values_;
};

}  // namespace pbf
