// The Python module's Engine (python/engine.hpp): the scene, the pipeline and runs.
#include "python/engine.hpp"

#include <fmt/format.h>
#include <omp.h>
#include <spdlog/spdlog.h>

#include "engine/core/compute.hpp"
#include "engine/core/fix.hpp"
#include "engine/core/interrupt.hpp"
#include "engine/core/scene_commands.hpp"
#include "engine/core/threads.hpp"
#include "engine/distributed/comm.hpp"
#include "engine/io/load_particles.hpp"
#include "engine/io/scene_file.hpp"
#include "engine/registry/style_registry.hpp"
#include "python/py_values.hpp"
#include "scripting/log_file.hpp"

namespace pbf::python {

namespace {

// A Python function called at the end of every `every`-th step, as Lua's pbf.every. An
// exception in it stops the run after the step, as Ctrl-C does (a restart to continue from);
// the exception is chained to the pbfengine.Interrupted the run raises.
class PythonCallback : public Fix {
 public:
  PythonCallback(Engine& engine, const std::string& id, std::int64_t every, py::object function)
      : Fix(id, "python"), engine_(engine), every_(every), function_(std::move(function)) {}
  ~PythonCallback() override {
    py::gil_scoped_acquire gil;
    function_ = py::object();
  }
  std::vector<Stage> stages() const override { return {Stage::end_of_step}; }
  bool runs_distributed() const override { return true; }  // every rank runs the program

  void end_of_step(Simulation& sim) override {
    if (sim.step() % every_ != 0) return;
    try {
      InterruptPause ctrl_c_reaches_python;  // a KeyboardInterrupt in the callback stops the run
      function_(sim.step(), sim.time());
    } catch (py::error_already_set& e) {
      engine_.set_callback_error(e.value());
      InterruptWatch::request_stop(e.matches(PyExc_KeyboardInterrupt)
                                       ? fmt::format("interrupted (Ctrl-C) in callback '{}'", id())
                                       : fmt::format("callback '{}' raised {}", id(), describe(e)));
    }
    engine_.particles_moved();  // views it took are stale once it returns
  }

 private:
  Engine& engine_;
  std::int64_t every_;
  py::object function_;
};

std::string python_str(py::handle value) { return py::str(value).cast<std::string>(); }

}  // namespace

Engine::Engine(std::optional<int> threads, std::optional<std::string> log, std::string log_level,
               bool check_every_hook) {
  static const std::vector<std::string> levels = {"trace", "debug", "info", "warn", "error", "off"};
  if (std::find(levels.begin(), levels.end(), log_level) == levels.end())
    throw Error(fmt::format("Simulation: log_level must be one of {}, got '{}'", fmt::join(levels, ", "), log_level));
  if (threads && (*threads < 1 || *threads > thread_limit()))
    throw Error(fmt::format("Simulation: threads must be from 1 to {}, got {}", thread_limit(), *threads));
  if (log && log->empty()) throw Error("Simulation: log needs a file name, or None for no log");
  log_file::setup_logging(comm::root() ? log_level : "off");
  if (log && comm::root()) {
    const std::string why = log_file::open(*log);
    if (!why.empty()) spdlog::warn("cannot open the log file '{}' ({}); the run goes on without a log", *log, why);
  } else {
    log_file::close();
  }
  const ThreadChoice choice =
      choose_threads(cores_of_this_process(comm::ranks_on_node()), threads, std::getenv("OMP_NUM_THREADS"));
  omp_set_num_threads(choice.threads);
  const char* s = choice.threads == 1 ? "" : "s";
  if (comm::distributed())
    spdlog::info("pbfengine {} (Python) on {} MPI ranks of {} OpenMP thread{} each ({})", PBF_VERSION, comm::ranks(),
                 choice.threads, s, choice.why);
  else
    spdlog::info("pbfengine {} (Python) on {} OpenMP thread{} ({})", PBF_VERSION, choice.threads, s, choice.why);
  for (const std::string& warning : choice.warnings) spdlog::warn("{}", warning);
  sim_ = std::make_unique<Simulation>();
  sim_->set_check_every_hook(check_every_hook);
}

Engine::~Engine() {
  script_.reset();  // its callbacks hold references into its Lua state
  sim_.reset();
}

void Engine::not_running(const char* what) const {
  if (running_) throw Error(fmt::format("{} cannot be called during a run (from a callback)", what));
}

Script& Engine::script() {
  if (!script_) {
    script_ = std::make_unique<Script>(*sim_);
    script_->set_interruptible(true);  // Ctrl-C in Lua code raises, the interpreter goes on
    // os.exit would end the Python process under the program's feet.
    script_->run_text("os.exit = function(code) error(string.format('os.exit(%s): a script run from Python cannot "
                      "end the process; raise an error instead', tostring(code)), 2) end",
                      "pbfengine");
  }
  return *script_;
}

void Engine::run_file(const std::string& path, const py::dict& variables) {
  not_running("run_file");
  std::vector<std::pair<std::string, std::string>> given;
  for (const auto& [name, value] : variables) {
    // As the command line's -v NAME=VALUE: text, which Lua converts as it converts numerals.
    const bool plain = py::isinstance<py::str>(value) || py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value);
    if (!plain)
      throw Error(fmt::format("run_file: variable '{}' is a {}; a -v variable is a str, int, float or bool",
                              python_str(name), python_str(py::type::of(value).attr("__name__"))));
    const std::string text = py::isinstance<py::bool_>(value) ? (value.cast<bool>() ? "true" : "false") : python_str(value);
    if (text.find('\0') != std::string::npos)
      throw Error(fmt::format("run_file: variable '{}' contains a zero byte", python_str(name)));
    given.emplace_back(python_str(name), text);
  }
  script().set_variables(given);
  particles_moved();
  guarded_run([&] { script().run_file(path); });
  for (const auto& warning : script().unread_variable_warnings()) spdlog::warn("{}", warning);
}

void Engine::lua(const std::string& statements) {
  not_running("lua");
  particles_moved();
  guarded_run([&] { script().run_text(statements, "lua"); });
}

py::dict Engine::domain(const py::kwargs& kwargs) {
  if (kwargs.size() > 0) {
    not_running("domain");
    sim_->set_domain(domain_from(Params("domain", domain_params(), given_params(kwargs, "domain"))));
  }
  const Domain& d = sim_->domain();
  py::list periodic;
  for (int a = 0; a < 3; ++a)
    if (d.periodic[a]) periodic.append(std::string(1, "xyz"[a]));
  py::dict result;
  result["lo"] = py::make_tuple(d.lo[0], d.lo[1], d.lo[2]);
  result["hi"] = py::make_tuple(d.hi[0], d.hi[1], d.hi[2]);
  result["periodic"] = periodic;
  return result;
}

std::size_t Engine::lattice(const py::kwargs& kwargs) {
  not_running("lattice");
  // `velocity` may be a function of position, applied to the particles added.
  py::kwargs given = kwargs;
  py::object velocity_function;
  if (given.contains("velocity") && py::isinstance<py::function>(given["velocity"])) {
    velocity_function = given["velocity"];
    given = py::kwargs(py::dict(kwargs));
    PyDict_DelItemString(given.ptr(), "velocity");
  }
  const LatticeAdded added = lattice_command(*sim_, Params("lattice", lattice_params(), given_params(given, "lattice")), "lattice");
  particles_moved();
  Particles& P = sim_->particles();
  if (velocity_function) try {
    for (std::size_t i = added.first; i < P.size(); ++i) {
      const double x = P.x()[i], y = P.y()[i], z = P.z()[i];
      const std::string what = fmt::format("lattice: the velocity function at ({:.6g}, {:.6g}, {:.6g})", x, y, z);
      py::object v;
      try {
        v = velocity_function(x, y, z);
      } catch (py::error_already_set& e) {
        throw Error(fmt::format("{} failed: {}", what, describe(e)));
      }
      const Vec3 u = vec3(v, fmt::format("{}: its result", what));
      for (double c : u)
        if (!std::isfinite(c)) throw Error(fmt::format("{} returned a velocity that is not finite", what));
      P.vx()[i] = real(u[0]);
      P.vy()[i] = real(u[1]);
      P.vz()[i] = real(u[2]);
    }
  } catch (...) {
    // A lattice is added whole or not at all: the program may catch the error and go on.
    std::vector<char> drop(P.size(), 0);
    std::fill(drop.begin() + static_cast<std::ptrdiff_t>(added.first), drop.end(), 1);
    P.remove(drop);
    P.set_next_id(P.next_id() - static_cast<std::int64_t>(added.added));
    sim_->positions_changed();
    throw;
  }
  return added.added;
}

std::size_t Engine::remove(const py::kwargs& kwargs) {
  not_running("delete");
  particles_moved();
  return delete_command(*sim_, Params("delete", delete_params(), given_params(kwargs, "delete")));
}

py::dict Engine::read_scene(const std::string& path) {
  not_running("read_scene");
  if (sim_->global_count() > 0)
    throw Error("read_scene: the scene file sets the domain, so read it before creating any particle");
  const SceneFile scene = read_scene_file(path);
  const double mass = load_scene(*sim_, scene);
  particles_moved();
  py::dict d;
  d["dt"] = scene.dt;
  d["h"] = scene.h;
  d["L"] = scene.L;
  d["interval"] = scene.interval;
  d["t_final"] = scene.t_final;
  d["mass"] = mass;
  d["count"] = scene.count;
  return d;
}

py::dict Engine::read_particles(const std::string& path) {
  not_running("read_particles");
  const LoadedParticles loaded = load_particle_file(*sim_, path);
  particles_moved();
  if (!loaded.ignored.empty()) spdlog::info("{}: columns not used: {}", path, fmt::join(loaded.ignored, ", "));
  py::dict d;
  d["count"] = loaded.count;
  d["mass"] = loaded.mass;
  return d;
}

void Engine::fix(const std::string& id, const std::string& style, const py::kwargs& kwargs) {
  not_running("fix");
  const std::string what = fmt::format("fix '{}' ({})", id, style);
  sim_->add_fix(StyleRegistry::builtin().make_fix(id, style, given_params(kwargs, what)));
}

void Engine::compute(const std::string& id, const std::string& style, const py::kwargs& kwargs) {
  not_running("compute");
  const std::string what = fmt::format("compute '{}' ({})", id, style);
  sim_->add_compute(StyleRegistry::builtin().make_compute(id, style, given_params(kwargs, what)));
}

// A number for a compute of one value, a dict by name for several, and for a per-particle
// compute a dict {"id": ids, "value": values} of arrays in id order (this rank's particles).
py::object Engine::value(const std::string& id) {
  Compute& c = compute_to_evaluate(*sim_, id, "value");
  std::vector<double> v;
  if (c.per_particle()) {
    std::vector<std::int64_t> ids;
    c.evaluate_per_particle(*sim_, ids, v);
    py::dict d;
    d["id"] = py::array_t<std::int64_t>(static_cast<py::ssize_t>(ids.size()), ids.data());
    d["value"] = py::array_t<double>(static_cast<py::ssize_t>(v.size()), v.data());
    return d;
  }
  c.evaluate(*sim_, v);
  const auto names = c.names();
  if (names.size() == 1) return py::float_(v.at(0));
  py::dict d;
  for (std::size_t k = 0; k < names.size(); ++k) d[py::str(names[k])] = v.at(k);
  return d;
}

void Engine::thermo(std::int64_t every, const std::vector<std::string>& columns, const std::string& csv) {
  not_running("thermo");
  if (every < 0) throw Error(fmt::format("thermo: 'every' must be >= 0, got {}", every));
  if (every > 1000000000) throw Error("thermo: 'every' is too large");
  sim_->thermo().configure(*sim_, static_cast<int>(every), columns, csv);
}

void Engine::every(const std::string& id, std::int64_t steps, py::object function) {
  not_running("every");
  if (steps < 1) throw Error(fmt::format("every: the interval must be at least 1 step, got {}", steps));
  if (!PyCallable_Check(function.ptr()))
    throw Error(fmt::format("every: the third argument must be a function, got {}",
                            python_str(py::type::of(function).attr("__name__"))));
  sim_->add_fix(std::make_unique<PythonCallback>(*this, id, steps, std::move(function)));
}

// A run: callbacks may not change the pipeline meanwhile; a callback's exception comes back
// chained to the Interrupted the stop raises.
template <class F>
void Engine::guarded_run(F&& run) {
  struct Running {
    bool& flag;
    ~Running() { flag = false; }
  } guard{running_};
  running_ = true;
  callback_error_ = py::object();
  particles_moved();
  try {
    run();
  } catch (const Interrupted& e) {
    if (!callback_error_) throw;
    py::object error = py::module_::import("pbfengine._pbfengine").attr("Interrupted")(e.what());
    error.attr("restart") = e.restart();
    PyException_SetCause(error.ptr(), callback_error_.release().ptr());  // steals the reference
    PyErr_SetObject(reinterpret_cast<PyObject*>(Py_TYPE(error.ptr())), error.ptr());
    throw py::error_already_set();
  }
}

void Engine::run(std::int64_t steps) {
  not_running("run");
  guarded_run([&] { sim_->run(steps); });
}

void Engine::run_until(double time) {
  not_running("run_until");
  guarded_run([&] { sim_->run_until(time); });
}

py::dict Engine::timing() const {
  const TimingTable& t = sim_->last_timing();
  py::dict d;
  d["wall"] = t.wall_seconds;
  d["particle_steps_per_second"] =
      t.wall_seconds > 0 ? double(t.steps) * double(t.particles) / t.wall_seconds : 0.0;
  py::list rows;
  for (const auto& row : t.rows()) {
    py::dict r;
    r["stage"] = row.stage;
    r["label"] = row.label;
    r["seconds"] = row.seconds;
    rows.append(r);
  }
  d["rows"] = rows;
  return d;
}

}  // namespace pbf::python
