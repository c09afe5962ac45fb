#include "engine/registry/params.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "engine/core/error.hpp"
#include "engine/core/names.hpp"
#include "engine/geometry/motion.hpp"
#include "engine/geometry/space_time_function.hpp"

namespace pbf {

const char* type_name(ParamType type) {
  switch (type) {
    case ParamType::Real: return "number";
    case ParamType::Integer: return "integer";
    case ParamType::Bool: return "boolean";
    case ParamType::String: return "string";
    case ParamType::Vector3: return "vector {x, y, z}";
    case ParamType::StringList: return "list of names";
    case ParamType::PointList: return "list of points {{x, y, z}, ...}";
    case ParamType::Motion: return "motion: function(t) or pbf.keyframes";
    case ParamType::Vector2: return "pair {a, b}";
    case ParamType::RealFunction: return "number or function(t, x, y, z)";
    case ParamType::Vector3Function: return "vector {x, y, z} or function(t, x, y, z)";
  }
  return "?";
}

std::string format_value(const ParamValue& value) {
  struct {
    std::string operator()(double v) const { return fmt::format("{}", v); }
    std::string operator()(std::int64_t v) const { return fmt::format("{}", v); }
    std::string operator()(bool v) const { return v ? "true" : "false"; }
    std::string operator()(const std::string& v) const { return fmt::format("\"{}\"", v); }
    std::string operator()(const Vec3& v) const { return fmt::format("{{{}, {}, {}}}", v[0], v[1], v[2]); }
    std::string operator()(const Names& v) const {
      std::string s;
      for (const auto& name : v) s += (s.empty() ? "\"" : ", \"") + name + "\"";
      return "{" + s + "}";
    }
    std::string operator()(const Points& v) const {
      std::string s;
      for (const auto& p : v) s += fmt::format("{}{{{}, {}, {}}}", s.empty() ? "" : ", ", p[0], p[1], p[2]);
      return "{" + s + "}";
    }
    std::string operator()(const MotionPtr& v) const { return v ? v->description() : "none"; }
    std::string operator()(const Vec2& v) const { return fmt::format("{{{}, {}}}", v[0], v[1]); }
    std::string operator()(const ScriptFunctionPtr& v) const { return v ? v->description() : "none"; }
    std::string operator()(const SpaceTimeFunctionPtr& v) const { return v ? v->description() : "none"; }
  } visitor;
  return std::visit(visitor, value);
}

namespace {

const char* given_type(const ParamValue& value) {
  struct {
    const char* operator()(double) const { return "number"; }
    const char* operator()(std::int64_t) const { return "integer"; }
    const char* operator()(bool) const { return "boolean"; }
    const char* operator()(const std::string&) const { return "string"; }
    const char* operator()(const Vec3&) const { return "vector"; }
    const char* operator()(const Names&) const { return "list of names"; }
    const char* operator()(const Points&) const { return "list of points"; }
    const char* operator()(const MotionPtr&) const { return "motion"; }
    const char* operator()(const Vec2&) const { return "pair"; }
    const char* operator()(const ScriptFunctionPtr&) const { return "function"; }
    const char* operator()(const SpaceTimeFunctionPtr&) const { return "function of time and place"; }
  } visitor;
  return std::visit(visitor, value);
}

// Converts a given value to the declared type, or returns nothing if it does not fit.
std::optional<ParamValue> coerce(const ParamValue& value, ParamType type) {
  switch (type) {
    case ParamType::Real:
      if (auto* d = std::get_if<double>(&value)) return *d;
      if (auto* i = std::get_if<std::int64_t>(&value)) return static_cast<double>(*i);
      return std::nullopt;
    case ParamType::Integer:
      if (auto* i = std::get_if<std::int64_t>(&value)) return *i;
      if (auto* d = std::get_if<double>(&value)) {  // integral floats (3.0) are integers
        if (std::isfinite(*d) && *d == std::floor(*d) && std::fabs(*d) < 9.0e15)
          return static_cast<std::int64_t>(*d);
      }
      return std::nullopt;
    case ParamType::Bool:
      if (auto* b = std::get_if<bool>(&value)) return *b;
      return std::nullopt;
    case ParamType::String:
      if (auto* s = std::get_if<std::string>(&value)) return *s;
      return std::nullopt;
    case ParamType::Vector3:
      if (auto* v = std::get_if<Vec3>(&value)) return *v;
      return std::nullopt;
    case ParamType::StringList:
      if (auto* v = std::get_if<Names>(&value)) return *v;
      if (auto* s = std::get_if<std::string>(&value)) return Names{*s};  // one name alone
      return std::nullopt;
    case ParamType::PointList:
      if (auto* v = std::get_if<Points>(&value)) return *v;
      if (auto* v = std::get_if<Vec3>(&value)) return Points{*v};  // one point alone
      if (auto* v = std::get_if<Names>(&value); v && v->empty()) return Points{};  // {}
      return std::nullopt;
    case ParamType::Motion:
      if (auto* v = std::get_if<MotionPtr>(&value)) return *v;
      if (auto* f = std::get_if<ScriptFunctionPtr>(&value)) return (*f)->motion();
      return std::nullopt;
    case ParamType::Vector2:
      if (auto* v = std::get_if<Vec2>(&value)) return *v;
      return std::nullopt;
    case ParamType::RealFunction:
    case ParamType::Vector3Function: {
      // A constant stays a number or a vector, checked as one (finite, within the range);
      // Params::function makes it a function when asked.
      const bool real = type == ParamType::RealFunction;
      if (auto constant = coerce(value, real ? ParamType::Real : ParamType::Vector3)) return constant;
      if (auto* f = std::get_if<ScriptFunctionPtr>(&value)) return (*f)->of_time_and_place(real ? 1 : 3);
      if (auto* f = std::get_if<SpaceTimeFunctionPtr>(&value)) return *f;
      return std::nullopt;
    }
  }
  return std::nullopt;
}

std::string names_of(const std::vector<ParamSpec>& schema) {
  std::string names;
  for (const auto& spec : schema) names += (names.empty() ? "" : ", ") + spec.name;
  return names.empty() ? "(none)" : names;
}

void check_range(const std::string& what, const ParamSpec& spec, const ParamValue& value) {
  auto check = [&](double v) {
    if (spec.range.contains(v)) return;
    const std::string range = spec.range.text();
    throw Error(fmt::format("{}: parameter '{}' must be {}{}{}, got {}", what, spec.name,
                            range[0] == '[' || range[0] == '(' ? "in " : "", range,
                            spec.unit.empty() ? "" : " " + spec.unit, format_value(value)));
  };
  if (auto* d = std::get_if<double>(&value)) check(*d);
  if (auto* i = std::get_if<std::int64_t>(&value)) check(static_cast<double>(*i));
  if (auto* v = std::get_if<Vec3>(&value))
    for (double c : *v) check(c);
  if (auto* v = std::get_if<Vec2>(&value))
    for (double c : *v) check(c);
  if (auto* v = std::get_if<Points>(&value))
    for (const auto& point : *v)
      for (double c : point) check(c);
  auto check_choice = [&](const std::string& text) {
    if (spec.choices.empty() || std::find(spec.choices.begin(), spec.choices.end(), text) != spec.choices.end()) return;
    if (spec.type == ParamType::StringList)
      throw Error(fmt::format("{}: parameter '{}' names \"{}\", which is not one of {}{}", what, spec.name, text,
                              spec.allowed(), did_you_mean(text, spec.choices)));
    throw Error(fmt::format("{}: parameter '{}' must be one of {}, got \"{}\"{}", what, spec.name, spec.allowed(), text,
                            did_you_mean(text, spec.choices)));
  };
  if (auto* text = std::get_if<std::string>(&value)) check_choice(*text);
  if (auto* names = std::get_if<Names>(&value))
    for (const std::string& text : *names) check_choice(text);
}

}  // namespace

std::string Range::text() const {
  const bool low = lo != -std::numeric_limits<double>::infinity(), high = hi != std::numeric_limits<double>::infinity();
  if (low && high) return fmt::format("{}{}, {}{}", lo_open ? "(" : "[", lo, hi, hi_open ? ")" : "]");
  if (low) return fmt::format("{} {}", lo_open ? ">" : ">=", lo);
  if (high) return fmt::format("{} {}", hi_open ? "<" : "<=", hi);
  return "any";
}

std::string ParamSpec::allowed() const {
  if (!choices.empty()) {
    std::string text;
    for (std::size_t k = 0; k < choices.size(); ++k)
      text += fmt::format("{}\"{}\"", k == 0 ? "" : k + 1 == choices.size() ? " or " : ", ", choices[k]);
    return text;
  }
  return range.limited() ? range.text() : "-";
}

Params::Params(const std::string& what, const std::vector<ParamSpec>& schema, const GivenParams& given) {
  for (const auto& [name, value] : given) {
    const ParamSpec* spec = nullptr;
    for (const auto& s : schema)
      if (s.name == name) spec = &s;
    if (!spec) {
      std::vector<std::string> valid;
      for (const auto& s : schema) valid.push_back(s.name);
      throw Error(fmt::format("{}: unknown parameter '{}'{}; valid parameters: {}", what, name,
                              did_you_mean(name, valid), names_of(schema)));
    }
    if (values_.count(name)) throw Error(fmt::format("{}: parameter '{}' given twice", what, name));
    auto converted = coerce(value, spec->type);
    if (!converted && spec->one_number_for_all)  // a scale of 2 is {2, 2, 2}
      if (auto number = coerce(value, ParamType::Real)) {
        const double v = std::get<double>(*number);
        converted = Vec3{v, v, v};
      }
    if (!converted)
      throw Error(fmt::format("{}: parameter '{}' must be of type {}, got {} {}", what, name, type_name(spec->type),
                              given_type(value), format_value(value)));
    if (auto* d = std::get_if<double>(&*converted); d && !std::isfinite(*d))
      throw Error(fmt::format("{}: parameter '{}' must be finite, got {}", what, name, *d));
    if (auto* v = std::get_if<Vec3>(&*converted))
      for (double c : *v)
        if (!std::isfinite(c)) throw Error(fmt::format("{}: parameter '{}' must be finite", what, name));
    if (auto* v = std::get_if<Points>(&*converted))
      for (std::size_t k = 0; k < v->size(); ++k)
        for (double c : (*v)[k])
          if (!std::isfinite(c))
            throw Error(fmt::format("{}: parameter '{}': point {} must be finite", what, name, k + 1));
    check_range(what, *spec, *converted);
    values_[name] = *converted;
  }
  for (const auto& spec : schema) {
    if (values_.count(spec.name) || spec.optional) continue;
    if (!spec.default_value) throw Error(fmt::format("{}: parameter '{}' is required", what, spec.name));
    values_[spec.name] = *spec.default_value;
  }
}

const ParamValue& Params::at(const std::string& name) const {
  auto it = values_.find(name);
  if (it == values_.end()) throw Error(fmt::format("internal: parameter '{}' not declared", name));
  return it->second;
}

double Params::real(const std::string& name) const { return std::get<double>(at(name)); }
std::int64_t Params::integer(const std::string& name) const { return std::get<std::int64_t>(at(name)); }
bool Params::boolean(const std::string& name) const { return std::get<bool>(at(name)); }
const std::string& Params::string(const std::string& name) const { return std::get<std::string>(at(name)); }
Vec3 Params::vec3(const std::string& name) const { return std::get<Vec3>(at(name)); }
Vec2 Params::vec2(const std::string& name) const { return std::get<Vec2>(at(name)); }
const Names& Params::names(const std::string& name) const { return std::get<Names>(at(name)); }
const Points& Params::points(const std::string& name) const { return std::get<Points>(at(name)); }
MotionPtr Params::motion(const std::string& name) const { return std::get<MotionPtr>(at(name)); }
SpaceTimeFunctionPtr Params::function(const std::string& name) const {
  const ParamValue& value = at(name);
  if (auto* f = std::get_if<SpaceTimeFunctionPtr>(&value)) return *f;
  if (auto* d = std::get_if<double>(&value)) return std::make_shared<ConstantFunction>(Vec3{*d, 0, 0}, 1);
  return std::make_shared<ConstantFunction>(std::get<Vec3>(value), 3);
}

}  // namespace pbf
