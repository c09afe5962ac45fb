// The Python module's compiled part, `pbfengine._pbfengine`: the engine's Simulation as
// `Engine`, which python/pbfengine/__init__.py extends into `pbfengine.Simulation` (the views
// of the particle arrays, their lifetime rules, the readers). Engine errors become
// pbfengine.Error with the engine's message; a run stopped by Ctrl-C or by a callback that
// raised becomes pbfengine.Interrupted, naming the restart it wrote.
//
// The interpreter's lock is held throughout: the engine's thread is the Python thread that
// called, and the OpenMP threads of the hot loops never touch Python, so a callback or a
// Python function given as a parameter is called directly.
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <omp.h>
#include <spdlog/spdlog.h>

#include "engine/core/compute.hpp"
#include "engine/core/field_array.hpp"
#include "engine/core/interrupt.hpp"
#include "engine/core/scene_commands.hpp"
#include "engine/core/simulation.hpp"
#include "engine/core/threads.hpp"
#include "engine/distributed/comm.hpp"
#include "engine/io/load_particles.hpp"
#include "engine/io/restart.hpp"
#include "engine/io/scene_file.hpp"
#include "engine/registry/style_registry.hpp"
#include "python/engine.hpp"
#include "python/py_values.hpp"
#include "scripting/log_file.hpp"

namespace py = pybind11;
using namespace pbf;
using pbf::python::Engine;

namespace {

py::dict restart_summary(const RestartSummary& r) {
  py::dict d;
  d["step"] = r.step;
  d["time"] = r.time;
  d["particles"] = r.particles;
  d["bytes"] = r.bytes;
  d["seconds"] = r.seconds;
  return d;
}

// What the engine prints goes to Python's sys.stdout and sys.stderr (a notebook shows them),
// from the thread that holds the interpreter; other threads (none log in a run today) write
// to the process's own.
void print_through_python(std::string_view text, bool error) {
  if (!PyGILState_Check()) {
    std::fwrite(text.data(), 1, text.size(), error ? stderr : stdout);
    return;
  }
  const py::object stream = py::module_::import("sys").attr(error ? "stderr" : "stdout");
  stream.attr("write")(py::str(text.data(), text.size()));
  stream.attr("flush")();
}

}  // namespace

PYBIND11_MODULE(_pbfengine, m) {
  m.doc() = "pbfengine's compiled core; use the pbfengine package (docs/python.md)";
  m.attr("version") = PBF_VERSION;
  m.attr("real") = sizeof(real) == 4 ? "float32" : "float64";

  static py::exception<Error> error(m, "Error", PyExc_RuntimeError);
  static py::exception<Interrupted> interrupted(m, "Interrupted", error.ptr());
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const Interrupted& e) {
      py::object exception = py::handle(interrupted.ptr())(e.what());
      exception.attr("restart") = e.restart();
      PyErr_SetObject(interrupted.ptr(), exception.ptr());
    } catch (const Error& e) {
      // The command line's debugging option is a Simulation's keyword here.
      std::string message = e.what();
      const std::string option = "--check-every-hook";
      if (auto at = message.find(option); at != std::string::npos)
        message.replace(at, option.size(), "Simulation(check_every_hook=True)");
      error(message.c_str());
    }
  });

  log_file::set_console(print_through_python);
  // Under an MPI launcher the ranks of a distributed run (mpi4py, when imported first, has
  // started MPI already: the engine joins it).
  int argc = 0;
  char** argv = nullptr;
  comm::start(argc, argv);
  py::module_::import("atexit").attr("register")(py::cpp_function([] {
    log_file::close();
    comm::stop();
  }));

  m.def("_pinned_blocks", &buffer_pins::pinned_blocks, "blocks of particle memory that views keep (for tests)");
  m.def("ranks", &comm::ranks, "the MPI ranks of the run (1 without a launcher)");
  m.def("rank", &comm::rank, "this process's rank (0 without a launcher)");
  m.def("keyframes", &python::keyframes, py::arg("keys"), py::arg("interpolation") = "linear",
        "a solid's motion through poses at given times: keys [{'t': T, 'translate': (x, y, z), "
        "'rotate': (rx, ry, rz)}, ...], linear or spline between them");
  py::class_<python::MotionHandle>(m, "Motion").def("__repr__", [](const python::MotionHandle& h) {
    return h.motion->description();
  });

  py::class_<Engine>(m, "Engine")
      .def(py::init<std::optional<int>, std::optional<std::string>, std::string, bool>(), py::arg("threads"),
           py::arg("log"), py::arg("log_level"), py::arg("check_every_hook"))
      // Lua: a scenario with its -v variables, or statements.
      .def("run_file", &Engine::run_file, py::arg("path"), py::arg("variables") = py::dict())
      .def("lua", &Engine::lua, py::arg("statements"))
      // The scene.
      .def("domain", &Engine::domain)
      .def("kernel_radius", &Engine::setting<&Simulation::kernel_radius, &Simulation::set_kernel_radius>,
           py::arg("h") = py::none())
      .def("timestep", &Engine::setting<&Simulation::timestep, &Simulation::set_timestep>, py::arg("dt") = py::none())
      .def("rest_density", &Engine::setting<&Simulation::rest_density, &Simulation::set_rest_density>,
           py::arg("rho") = py::none())
      .def("lattice", &Engine::lattice)
      .def("delete", &Engine::remove)
      .def("read_scene", &Engine::read_scene, py::arg("path"))
      .def("read_particles", &Engine::read_particles, py::arg("path"))
      .def("write_restart",
           [](Engine& e, const std::string& path) {
             e.not_running("write_restart");
             if (e.sim().particle_mass() == 0) throw Error("write_restart: there are no particles to save");
             return restart_summary(write_restart(e.sim(), path));
           },
           py::arg("path"))
      .def("read_restart",
           [](Engine& e, const std::string& path) {
             e.not_running("read_restart");
             if (e.sim().global_count() > 0)
               throw Error("read_restart replaces the scene: call it before creating any particle");
             e.particles_moved();
             return restart_summary(read_restart(e.sim(), path));
           },
           py::arg("path"))
      // The pipeline.
      .def("fix", &Engine::fix, py::arg("id"), py::arg("style"))
      .def("unfix", [](Engine& e, const std::string& id) { e.not_running("unfix"), e.sim().remove_fix(id); })
      .def("compute", &Engine::compute, py::arg("id"), py::arg("style"))
      .def("uncompute", [](Engine& e, const std::string& id) { e.not_running("uncompute"), e.sim().remove_compute(id); })
      .def("value", &Engine::value, py::arg("id"))
      .def("thermo", &Engine::thermo, py::arg("every") = 100, py::arg("columns") = std::vector<std::string>{"step", "time"},
           py::arg("csv") = "")
      .def("every", &Engine::every, py::arg("id"), py::arg("steps"), py::arg("function"))
      .def("run", &Engine::run, py::arg("steps"))
      .def("run_until", &Engine::run_until, py::arg("time"))
      .def_property_readonly("step", [](Engine& e) { return e.sim().step(); })
      .def_property_readonly("time", [](Engine& e) { return e.sim().time(); })
      .def_property_readonly("count", [](Engine& e) { return e.sim().global_count(); })
      .def_property_readonly("rank_count", [](Engine& e) { return e.sim().particles().size(); })
      .def("timing", &Engine::timing)
      .def("outputs", [](Engine& e) { return e.sim().outputs().summary(); })
      // The particle arrays (python/engine_arrays.cpp).
      .def("fields", &Engine::fields)
      .def("_view", &Engine::view, py::arg("name"), py::arg("component"), py::arg("writable"))
      .def("_ids", &Engine::ids)
      .def("_address", &Engine::address, py::arg("name"), py::arg("component"))
      .def_property_readonly("_epoch", &Engine::epoch)
      .def("gather", &Engine::gather, py::arg("name"));
}
