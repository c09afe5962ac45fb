#pragma once
// Python values as the engine's: keyword arguments as style and scene parameters (checked by
// the same schemas as Lua's tables), Python functions as the functions a parameter may be (a
// solid's motion, an emitter's speed), keyframes as motions. The Python module's only
// conversions; python/module.cpp binds the rest.
#include <pybind11/pybind11.h>

#include <string>

#include "engine/geometry/motion.hpp"
#include "engine/registry/params.hpp"

namespace pbf::python {

namespace py = pybind11;

// A keyword argument's value: bool, int, float, str, a function, a motion, or a sequence
// (three numbers, two numbers, names, or points of three numbers each).
ParamValue param_value(py::handle value, const std::string& name);
// Keyword arguments as parameters, sorted by name as Lua's table_params gives them.
GivenParams given_params(const py::kwargs& kwargs, const std::string& what);
// A motion as Python holds it (pbfengine.Motion).
struct MotionHandle {
  MotionPtr motion;
};
// pbfengine.keyframes([{t=, translate=, rotate=}, ...], interpolation="linear").
MotionHandle keyframes(const py::list& keys, const std::string& interpolation);
// Three finite numbers from a sequence, or Error naming `what`.
Vec3 vec3(py::handle value, const std::string& what);
// The Python exception being handled, as one line "TypeError: message".
std::string describe(const py::error_already_set& e);

}  // namespace pbf::python
