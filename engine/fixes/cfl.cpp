// cfl: time-step control, for explicit solvers (WCSPH) and for PBF. At the end of every step
// (and when a run starts) it sets the next step's size to
//   dt = min(max_dt, courant h / (c + |v|max), force sqrt(h / |a|max), viscous h_s^2 / nu, dt_solver)
// with h the kernel support radius, c the largest signal speed of the pipeline's fixes (the
// wcsph sound speed; none for pbf) unless given, |a|max from the integrator's "acceleration"
// field, and |v|max the fastest particle or moving solid (over the step now set), so a wall
// moves less than a fraction of h in a step. The viscous limit (Morris et al. 1997, with
// viscous = 0.125 and h_s = h / 2 the smoothing length) holds an explicit viscosity nu (the
// largest a fix applies: sph_viscosity's Laplacian form) below the step at which momentum
// diffuses farther than the kernel in one step; with water's nu it is seconds, and matters
// only for viscous fluids and fine resolutions.
//
// dt_solver (only with `iterations`) is the largest step in which the constraint solver meets
// its accuracy target (pbf's `error`) within N = `iterations` iterations. With n the
// iterations the last step of size dt took:
//   n > N:                              dt_solver = dt max(N / n, 0.8)
//   n < N, from a step dt_solver chose:  dt_solver = 1.05 dt
//   n = N:                              it stays.
// It starts from the step the script set. It changes by a fifth a step at most: a PBF step
// turns the compression it removes into velocity, dx / dt, so a step much shorter than the
// one before throws the fluid apart (docs/physics.md, "Time step").
//
// With `align` > 0 a step that would pass the next multiple of align (from the fix's start) is
// shortened to end on it, so frames on that interval land on their times. Thermo's dt
// column shows the step it chose.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "engine/core/error.hpp"
#include "engine/core/parallel.hpp"
#include "engine/registry/builtin_styles.hpp"
#include "engine/io/bytes.hpp"
#include "engine/core/simulation.hpp"
#include "engine/distributed/comm.hpp"
#include "engine/geometry/solid_body.hpp"

namespace pbf {

namespace {

class Cfl : public Fix {
 public:
  Cfl(const std::string& id, const Params& p)
      : Fix(id, "cfl"),
        courant_(p.real("courant")),
        force_(p.real("force")),
        max_dt_(p.real("max_dt")),
        c_(p.real("sound_speed")),
        align_(p.real("align")),
        viscous_(p.real("viscous")),
        target_iterations_(static_cast<int>(p.integer("iterations"))) {}

  std::vector<Stage> stages() const override { return {Stage::end_of_step}; }
  std::vector<const char*> exclusive_jobs() const override { return {"time-step control"}; }
  bool runs_distributed() const override { return true; }  // the largest speed and acceleration of all ranks

  void init(Simulation& sim) override {
    if (!started_) {
      started_ = true;
      if (max_dt_ == 0) max_dt_ = sim.timestep();  // the script's step is the upper bound
      start_ = sim.time();
      solver_dt_ = std::min(max_dt_, sim.timestep());  // from the script's step, growing as the solver allows
    }
    if (watches_solver()) {
      const Fix* integrator = sim.integrator();
      if (!integrator || integrator->integration() != Integration::positions)
        throw Error("'iterations' needs a constraint solver that reports them (pbf, with an accuracy target 'error')");
    }
    choose(sim);
  }

  void end_of_step(Simulation& sim) override {
    if (watches_solver()) follow_solver(sim);
    choose(sim);
  }

  void save_state(ByteWriter& w) const override {
    w.put<std::uint8_t>(started_);
    w.put(max_dt_);
    w.put(start_);
    w.put(solver_dt_);
  }
  void restore_state(ByteReader& r) override {
    started_ = r.get<std::uint8_t>() != 0;
    max_dt_ = r.get<double>();
    start_ = r.get<double>();
    solver_dt_ = r.get<double>();
  }

 private:
  bool watches_solver() const { return target_iterations_ > 0; }

  // dt_solver from the iterations of the step just taken (see the top).
  void follow_solver(Simulation& sim) {
    const int n = sim.solver_report().constraints.iterations;
    const double dt = sim.timestep();
    if (n > target_iterations_)
      solver_dt_ = dt * std::max(0.8, double(target_iterations_) / n);
    else if (n < target_iterations_ && dt >= solver_dt_ * (1 - 1e-12))
      solver_dt_ = std::min(max_dt_, 1.05 * dt);
  }

  void choose(Simulation& sim) {
    const auto& P = sim.particles();
    const std::size_t n = P.size();
    const double c = c_ > 0 ? c_ : sim.max_signal_speed();
    double v2 = 0, a2 = 0;
    const auto accel = P.find("acceleration");
#pragma omp parallel for schedule(dynamic, kStreamBlock) reduction(max : v2, a2)
    for (std::size_t i = 0; i < n; ++i) {
      v2 = std::max(v2, double(P.vx()[i]) * P.vx()[i] + double(P.vy()[i]) * P.vy()[i] + double(P.vz()[i]) * P.vz()[i]);
      if (accel) {
        const double ax = P.data(*accel, 0)[i], ay = P.data(*accel, 1)[i], az = P.data(*accel, 2)[i];
        a2 = std::max(a2, ax * ax + ay * ay + az * az);
      }
    }
    if (P.distributed()) {
      double most[2] = {v2, a2};
      comm::max(most);
      v2 = most[0];
      a2 = most[1];
    }
    for (const SolidBody* solid : sim.solid_bodies()) {
      const double speed = solid->max_speed(sim.time(), sim.timestep());
      v2 = std::max(v2, speed * speed);
    }
    const double h = sim.kernel_radius();
    double dt = watches_solver() ? std::min(max_dt_, solver_dt_) : max_dt_;
    if (c + std::sqrt(v2) > 0) dt = std::min(dt, courant_ * h / (c + std::sqrt(v2)));
    if (a2 > 0) dt = std::min(dt, force_ * std::sqrt(h / std::sqrt(a2)));
    if (const double nu = sim.max_kinematic_viscosity(); nu > 0) dt = std::min(dt, viscous_ * (h / 2) * (h / 2) / nu);
    if (align_ > 0) {
      // The next multiple of align after now; a remainder far below a step counts as reached.
      const double elapsed = sim.time() - start_;
      double next = std::ceil(elapsed / align_) * align_;
      if (next - elapsed < 1e-6 * dt) next += align_;
      dt = std::min(dt, next - elapsed);
    }
    if (dt != sim.timestep()) sim.set_timestep(dt);
  }

  double courant_, force_, max_dt_, c_, align_, viscous_;
  int target_iterations_;
  bool started_ = false;
  double start_ = 0, solver_dt_ = 0;
};

}  // namespace

void register_cfl(StyleRegistry& r) {
  r.add({"cfl",
         StyleKind::fix,
         "time-step control: dt = min(max_dt, courant h/(c + |v|max), force sqrt(h/|a|max), viscous (h/2)^2/nu, "
         "solver bound), chosen every step",
         {ParamSpec{"courant", ParamType::Real, 0.15, "",
                    "Courant number on h / (c + |v|max), h the support radius (above 1 a step outruns the signal)"}
              .above_within(0, 1),
          ParamSpec{"force", ParamType::Real, 0.15, "", "factor of the force criterion sqrt(h / |a|max)"}.above_within(0, 1),
          ParamSpec{"viscous", ParamType::Real, 0.125, "",
                    "factor of the viscous limit (h/2)^2 / nu, nu the largest explicit viscosity (sph_viscosity's "
                    "Laplacian nu)"}
              .above_within(0, 1),
          ParamSpec{"max_dt", ParamType::Real, 0.0, "s", "largest step (0: the time step the script set)"}.at_least(0),
          ParamSpec{"sound_speed", ParamType::Real, 0.0, "m/s", "c (0: the largest signal speed of the fixes, wcsph's c0)"}
              .within(0, kMostSoundSpeed),
          ParamSpec{"align", ParamType::Real, 0.0, "s", "end steps on multiples of this interval (0: no alignment)"}
              .at_least(0),
          ParamSpec{"iterations", ParamType::Integer, std::int64_t{0}, "",
                    "largest step in which pbf reaches its accuracy target ('error') in at most this many "
                    "iterations (0: not used)"}
              .within(0, 1000)},
         [](const std::string& id, const Params& p) { return std::make_unique<Cfl>(id, p); }, nullptr});
}

}  // namespace pbf
