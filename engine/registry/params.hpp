#pragma once
// Style parameters as data: each style declares a schema (name, type, default, unit, doc);
// values given by a script are checked against it before the style is constructed.
#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace pbf {

enum class ParamType { Real, Integer, Bool, String, Vector3, StringList };
const char* type_name(ParamType type);

using Vec3 = std::array<double, 3>;
using Names = std::vector<std::string>;
using ParamValue = std::variant<double, std::int64_t, bool, std::string, Vec3, Names>;

std::string format_value(const ParamValue& value);

struct ParamSpec {
  std::string name;
  ParamType type;
  std::optional<ParamValue> default_value;  // none: the parameter is required
  std::string unit;                         // "" for dimensionless
  std::string doc;                          // one line
  bool optional = false;                    // no default, and may be left out (Params::has)
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
  const Names& names(const std::string& name) const;
  bool has(const std::string& name) const { return values_.count(name) > 0; }
  const std::map<std::string, ParamValue>& values() const { return values_; }

 private:
  const ParamValue& at(const std::string& name) const;
  std::map<std::string, ParamValue> values_;
};

}  // namespace pbf
