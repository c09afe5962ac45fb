// Python values as the engine's (python/py_values.hpp).
#include "python/py_values.hpp"

#include <cmath>
#include <fmt/format.h>

#include "engine/core/error.hpp"
#include "engine/geometry/space_time_function.hpp"

namespace pbf::python {

namespace {

// A number, not a bool (Python's or NumPy's, which convert to 1 and 0 silently).
bool is_number(py::handle v) {
  if (py::isinstance<py::bool_>(v) || py::isinstance<py::str>(v)) return false;
  if (py::hasattr(v, "dtype") && py::str(v.attr("dtype").attr("kind")).cast<std::string>() == "b") return false;
  return py::isinstance<py::int_>(v) || py::isinstance<py::float_>(v) || py::hasattr(v, "__float__");
}

std::string type_of(py::handle v) { return py::type::of(v).attr("__name__").cast<std::string>(); }

// A number's value, or Error: a value beyond a double (10**400), an array that is no scalar.
double number_of(py::handle v, const std::string& what) {
  double x = 0;
  try {
    x = v.cast<double>();
  } catch (const py::error_already_set&) {
    throw Error(fmt::format("{}: {} is not a number a double can hold", what, py::repr(v).cast<std::string>()));
  } catch (const py::cast_error&) {
    throw Error(fmt::format("{}: a {} is not a number", what, type_of(v)));
  }
  return x;
}

// Mappings, sets and bytes are sequences of something else than a value (their keys, their
// bytes): refused rather than read as a vector or names.
bool refused_container(py::handle v) {
  return py::isinstance<py::dict>(v) || py::isinstance<py::bytes>(v) || PyAnySet_Check(v.ptr()) ||
         py::isinstance<py::bytearray>(v);
}

// Text that crosses into the engine, whose messages and file names end at a zero byte.
std::string text_of(py::handle v, const std::string& what) {
  std::string text = v.cast<std::string>();
  if (text.find('\0') != std::string::npos)
    throw Error(fmt::format("{} contains a zero byte", what));
  return text;
}

// A function's "defined at FILE:LINE", for messages (Python's own functions; others by name).
std::string where(const py::handle function) {
  try {
    const py::object code = function.attr("__code__");
    return fmt::format("{}:{}", code.attr("co_filename").cast<std::string>(),
                       code.attr("co_firstlineno").cast<int>());
  } catch (const py::error_already_set&) {
    return py::repr(function).cast<std::string>();
  }
}

// Calls a Python function from the engine (with the interpreter's lock, which the engine's
// thread holds throughout a run); a Python error becomes the engine's Error.
py::object call(const py::object& function, const std::string& what, py::args args) {
  try {
    return function(*args);
  } catch (py::error_already_set& e) {
    throw Error(fmt::format("{}: {}", what, describe(e)), true);
  }
}

// function(t, x, y, z) returning a number (components 1) or three numbers (3).
class PythonSpaceTime : public SpaceTimeFunction {
 public:
  PythonSpaceTime(py::object function, int components) : function_(std::move(function)), components_(components) {}
  ~PythonSpaceTime() override {
    py::gil_scoped_acquire gil;
    function_ = py::object();
  }
  Vec3 at(double t, const Vec3& x) const override {
    const std::string what = fmt::format("{} at t = {} s, (x, y, z) = ({:.6g}, {:.6g}, {:.6g})", description(), t,
                                         x[0], x[1], x[2]);
    const py::object result = call(function_, what, py::make_tuple(t, x[0], x[1], x[2]));
    if (components_ == 3) return vec3(result, fmt::format("{}: its result", what));
    if (!is_number(result) || py::hasattr(result, "__len__"))
      throw Error(fmt::format("{} returned a {}, not a number", what, type_of(result)));
    return {number_of(result, what), 0, 0};
  }
  bool constant() const override { return false; }
  std::string description() const override { return fmt::format("the function ({})", where(function_)); }

 private:
  py::object function_;
  int components_;
};

// function(t) returning {"translate": (x, y, z), "rotate": (rx, ry, rz)}, either left out.
class PythonMotion : public Motion {
 public:
  explicit PythonMotion(py::object function) : function_(std::move(function)) {}
  ~PythonMotion() override {
    py::gil_scoped_acquire gil;
    function_ = py::object();
  }
  Pose at(double t) const override {
    const std::string what = fmt::format("the motion {} at t = {}", description(), t);
    const py::object result = call(function_, what, py::make_tuple(t));
    if (!py::isinstance<py::dict>(result))
      throw Error(fmt::format("{} returned a {}, not a dict {{\"translate\": (x, y, z), \"rotate\": (rx, ry, rz)}}",
                              what, py::type::of(result).attr("__name__").cast<std::string>()));
    Pose pose;
    for (const auto& [key, value] : result.cast<py::dict>()) {
      const std::string name = py::str(key);
      if (name == "translate") pose.translate = vec3(value, fmt::format("{}: 'translate'", what));
      else if (name == "rotate") pose.rotate_deg = vec3(value, fmt::format("{}: 'rotate'", what));
      else throw Error(fmt::format("{} returned the key '{}'; a pose has 'translate' and 'rotate'", what, name));
    }
    check_pose(pose, what);
    return pose;
  }
  std::string description() const override { return fmt::format("function ({})", where(function_)); }

 private:
  py::object function_;
};

class PythonFunction : public ScriptFunction {
 public:
  explicit PythonFunction(py::object function) : function_(std::move(function)) {}
  ~PythonFunction() override {
    py::gil_scoped_acquire gil;
    function_ = py::object();
  }
  MotionPtr motion() const override { return std::make_shared<PythonMotion>(function_); }
  SpaceTimeFunctionPtr of_time_and_place(int components) const override {
    return std::make_shared<PythonSpaceTime>(function_, components);
  }
  std::string description() const override { return fmt::format("defined at {}", where(function_)); }

 private:
  py::object function_;
};

const char* kValues = "number, bool, str, (x, y, z), [\"name\", ...], [(x, y, z), ...], a function or a motion";

}  // namespace

std::string describe(const py::error_already_set& e) {
  std::string type = "an exception", text;
  try {
    type = e.type().attr("__name__").cast<std::string>();
    text = py::str(e.value()).cast<std::string>();
  } catch (const py::error_already_set&) {
    text = "(its message cannot be shown: str() of it failed)";
  } catch (const py::cast_error&) {
    text = "(its message cannot be shown)";
  }
  return text.empty() ? type : fmt::format("{}: {}", type, text);
}

Vec3 vec3(py::handle value, const std::string& what) {
  if (py::isinstance<py::str>(value) || refused_container(value) ||
      (!py::isinstance<py::sequence>(value) && !py::hasattr(value, "__len__")))
    throw Error(fmt::format("{} must be three numbers (x, y, z), got a {}", what, type_of(value)));
  const py::list s(py::reinterpret_borrow<py::object>(value));
  if (s.size() != 3) throw Error(fmt::format("{} must be three numbers (x, y, z), got {} values", what, s.size()));
  Vec3 v{};
  for (std::size_t k = 0; k < 3; ++k) {
    if (!is_number(s[k]) || py::hasattr(s[k], "__len__"))
      throw Error(fmt::format("{}: component {} is a {}, not a number", what, k + 1, type_of(s[k])));
    v[k] = number_of(s[k], fmt::format("{}: component {}", what, k + 1));
  }
  return v;
}

ParamValue param_value(py::handle value, const std::string& name) {
  const std::string what = fmt::format("parameter '{}'", name);
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>();
  if (py::isinstance<py::int_>(value)) {
    try {
      return value.cast<std::int64_t>();
    } catch (const py::cast_error&) {
      throw Error(fmt::format("{}: the integer {} does not fit in 64 bits", what, py::str(value).cast<std::string>()));
    }
  }
  if (py::isinstance<py::float_>(value)) return value.cast<double>();
  if (py::isinstance<py::str>(value)) return text_of(value, what);
  if (refused_container(value))
    throw Error(fmt::format("{}: a {} is not a parameter value ({})", what, type_of(value), kValues));
  if (py::isinstance<MotionHandle>(value)) return value.cast<const MotionHandle&>().motion;
  if (py::isinstance<py::function>(value) || (py::hasattr(value, "__call__") && !py::hasattr(value, "__len__")))
    return ScriptFunctionPtr(std::make_shared<PythonFunction>(py::reinterpret_borrow<py::object>(value)));
  // NumPy scalars: numbers by their kind.
  if (py::hasattr(value, "dtype") && py::hasattr(value, "item") && !py::hasattr(value, "__len__"))
    return param_value(value.attr("item")(), name);
  if (!py::isinstance<py::sequence>(value) && !py::hasattr(value, "__len__"))
    throw Error(fmt::format("{}: a {} is not a parameter value ({})", what,
                            py::type::of(value).attr("__name__").cast<std::string>(), kValues));
  const py::list items(py::reinterpret_borrow<py::object>(value));
  if (items.empty()) return Names{};
  if (py::isinstance<py::str>(items[0])) {
    Names names;
    for (std::size_t k = 0; k < items.size(); ++k) {
      if (!py::isinstance<py::str>(items[k]))
        throw Error(fmt::format("{}: entry {} of a list of names is a {}, not a str", what, k + 1,
                                py::type::of(items[k]).attr("__name__").cast<std::string>()));
      names.push_back(text_of(items[k], fmt::format("{}: entry {}", what, k + 1)));
    }
    return names;
  }
  if (!is_number(items[0])) {  // points
    Points points;
    for (std::size_t k = 0; k < items.size(); ++k) points.push_back(vec3(items[k], fmt::format("{}: point {}", what, k + 1)));
    return points;
  }
  if (items.size() == 2) {
    Vec2 v{};
    for (std::size_t k = 0; k < 2; ++k) {
      if (!is_number(items[k])) throw Error(fmt::format("{} must be a pair of numbers (a, b)", what));
      v[k] = number_of(items[k], what);
    }
    return v;
  }
  if (items.size() != 3)
    throw Error(fmt::format("{} must be a vector (x, y, z) or a list of names, got {} numbers", what, items.size()));
  return vec3(items, what);
}

GivenParams given_params(const py::kwargs& kwargs, const std::string& what) {
  GivenParams given;
  for (const auto& [key, value] : kwargs) {
    const std::string name = py::str(key);
    try {
      if (name.find('\0') != std::string::npos) throw Error("a parameter name contains a zero byte");
      given.emplace_back(name, param_value(value, name));
    } catch (const Error& e) {
      throw Error(fmt::format("{}: {}", what, e.what()));
    }
  }
  std::sort(given.begin(), given.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  return given;
}

MotionHandle keyframes(const py::list& keys, const std::string& interpolation) {
  const std::string what = "keyframes";
  Keyframes::Interpolation kind = Keyframes::Interpolation::linear;
  if (interpolation == "spline") kind = Keyframes::Interpolation::spline;
  else if (interpolation != "linear")
    throw Error(fmt::format("{}: 'interpolation' must be \"linear\" or \"spline\", got \"{}\"", what, interpolation));
  std::vector<Keyframes::Key> frames;
  for (std::size_t k = 0; k < keys.size(); ++k) {
    const std::string key_what = fmt::format("{}: key {}", what, k + 1);
    if (!py::isinstance<py::dict>(keys[k]))
      throw Error(fmt::format("{} must be a dict {{\"t\": T, \"translate\": (x, y, z), \"rotate\": (rx, ry, rz)}}",
                              key_what));
    Keyframes::Key key;
    bool has_t = false;
    for (const auto& [name_object, value] : keys[k].cast<py::dict>()) {
      const std::string name = py::str(name_object);
      if (name == "t") {
        if (!is_number(value)) throw Error(fmt::format("{}: 't' must be a number", key_what));
        key.t = number_of(value, fmt::format("{}: 't'", key_what));
        has_t = true;
      } else if (name == "translate") {
        key.pose.translate = vec3(value, fmt::format("{}: 'translate'", key_what));
      } else if (name == "rotate") {
        key.pose.rotate_deg = vec3(value, fmt::format("{}: 'rotate'", key_what));
      } else {
        throw Error(fmt::format("{}: unknown entry '{}'; a key has 't', 'translate' and 'rotate'", key_what, name));
      }
    }
    if (!has_t) throw Error(fmt::format("{}: 't' is missing", key_what));
    frames.push_back(key);
  }
  return {std::make_shared<Keyframes>(std::move(frames), kind, what)};
}

}  // namespace pbf::python
