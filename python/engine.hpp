#pragma once
// The Python module's Engine: one Simulation, the Lua state that runs scenarios and statements
// against it (made on first use), and what Python asks of them. python/module.cpp binds it.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/core/simulation.hpp"
#include "scripting/script.hpp"

namespace pbf::python {

namespace py = pybind11;

class Engine {
 public:
  Engine(std::optional<int> threads, std::optional<std::string> log, std::string log_level, bool check_every_hook);
  ~Engine();
  Engine(const Engine&) = delete;
  Engine& operator=(const Engine&) = delete;

  Simulation& sim() { return *sim_; }
  // Changing the scene or the pipeline from a callback inside a run is not allowed.
  void not_running(const char* what) const;
  // The particles moved in memory (a run, new or removed particles, a restart read): views
  // taken before are stale (python/pbfengine/_views.py).
  void particles_moved() { ++epoch_; }
  std::uint64_t epoch() const { return epoch_; }

  void run_file(const std::string& path, const py::dict& variables);
  void lua(const std::string& statements);

  py::dict domain(const py::kwargs& kwargs);
  template <double (Simulation::*Get)() const, void (Simulation::*Set)(double)>
  double setting(std::optional<double> value) {
    if (value) {
      not_running("a setting");
      (sim_.get()->*Set)(*value);
    }
    return (sim_.get()->*Get)();
  }
  std::size_t lattice(const py::kwargs& kwargs);
  std::size_t remove(const py::kwargs& kwargs);
  py::dict read_scene(const std::string& path);
  py::dict read_particles(const std::string& path);

  void fix(const std::string& id, const std::string& style, const py::kwargs& kwargs);
  void compute(const std::string& id, const std::string& style, const py::kwargs& kwargs);
  py::object value(const std::string& id);
  void thermo(std::int64_t every, const std::vector<std::string>& columns, const std::string& csv);
  // function(step, time) at the end of every `steps`-th step.
  void every(const std::string& id, std::int64_t steps, py::object function);
  void run(std::int64_t steps);
  void run_until(double time);
  py::dict timing() const;

  // --- the particle arrays (python/engine_arrays.cpp) ---
  // [(name, components, doc)] of the live fields.
  py::list fields() const;
  // A NumPy array over component `component` of the field, this rank's particles, in memory
  // order; it pins the memory (engine/core/field_array.hpp).
  py::array view(const std::string& name, int component, bool writable);
  py::array ids();
  std::uintptr_t address(const std::string& name, int component);
  // Every rank's values of the field in id order, on rank 0 (None elsewhere): {"id": ...,
  // "NAME": (N,) or (N, components)}. Collective.
  py::object gather(const std::string& name);

  // A callback raised: the exception, kept to chain to the Interrupted the run ends with.
  void set_callback_error(py::object error) { callback_error_ = std::move(error); }

 private:
  Script& script();
  template <class F>
  void guarded_run(F&& run);
  FieldId field_id(const std::string& name) const;

  std::unique_ptr<Simulation> sim_;
  std::unique_ptr<Script> script_;
  bool running_ = false;
  std::uint64_t epoch_ = 0;
  py::object callback_error_;
};

}  // namespace pbf::python
