// The run loop's checks (engine/core/run_loop.hpp): what a run must be able to do before it
// starts, what each hook must leave behind, and the stops a signal or a blow-up makes.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "engine/core/error.hpp"
#include "engine/core/interrupt.hpp"
#include "engine/core/parallel.hpp"
#include "engine/core/run_loop.hpp"
#include "engine/io/restart.hpp"

namespace pbf {

// What no single fix can see: a force style without an integrator of accelerations.
// (Two fixes with one job, two integrators among them, are refused when added.)
void RunLoop::check_pipeline() const {
  const Fix* integrator = sim_.integrator();
  for (const auto& f : sim_.fixes_) {
    if (!f->adds_accelerations() || (integrator && applies_accelerations(integrator->integration()))) continue;
    std::string message = fmt::format("fix '{}' ({}): {} adds accelerations, but no fix integrates them", f->id(),
                                      f->style(), f->style());
    if (integrator)
      message += fmt::format(" (fix '{}' ({}) moves positions itself: use one solver)", integrator->id(),
                             integrator->style());
    else
      message += ": add pbf.fix(\"integrator\", \"leapfrog\", {})";
    throw Error(message);
  }
}

// How long the run takes, decided before anything starts: a run that would not end in any
// reasonable time, or whose steps no longer move the clock, is refused instead of left to spin.
void RunLoop::plan(std::int64_t steps, double until) {
  const double t = sim_.time(), dt = sim_.dt_;
  const std::string what = steps >= 0 ? fmt::format("run({})", steps) : fmt::format("run_until({})", until);
  if (t + dt == t)
    throw Error(fmt::format("{}: the time step {} s vanishes against the time {} s (t + dt == t): the clock cannot "
                            "advance",
                            what, dt, t));
  const double count = steps >= 0 ? static_cast<double>(steps) : std::max(0.0, std::ceil((until - t) / dt - 1e-9));
  if (count > kMostSteps)
    throw Error(fmt::format("{}: from t = {} s at dt = {} s that is {:.3g} steps, more than {:.0e}: an end time or a "
                            "time step in the wrong unit?",
                            what, t, dt, count, kMostSteps));
  if (count > kManySteps)
    spdlog::warn("{}: {:.3g} steps of {} s ahead (more than {:.0e}): this run will take long", what, count, dt,
                 kManySteps);
  sim_.run_plan_ = {count, steps >= 0 ? t + count * dt : until};
}

void RunLoop::check_masses() const {
  const auto& P = sim_.particles_;
  const real* m = P.mass();
  for (std::size_t i = 0; i < P.size(); ++i)
    if (!(m[i] > 0) || !std::isfinite(m[i]))
      throw Error(fmt::format("particle {} has mass {} kg: a particle's mass must be positive and finite; the run "
                              "cannot start",
                              P.ids()[i], m[i]));
}

// The state a run starts from must be one a step can advance: finite, and no particle so
// fast that one step carries it across the whole domain (it would leave at once).
void RunLoop::check_start_state() const {
  const auto& P = sim_.particles_;
  if (const std::size_t i = first_non_finite(); i < P.size())
    throw Error(fmt::format("particle {} has a non-finite position or velocity ({} {} {}, {} {} {}): the run cannot start",
                            P.ids()[i], P.x()[i], P.y()[i], P.z()[i], P.vx()[i], P.vy()[i], P.vz()[i]));
  double widest = 0;
  for (int a = 0; a < 3; ++a) widest = std::max(widest, sim_.domain_.extent(a));
  const real* v[3] = {P.vx(), P.vy(), P.vz()};
  for (std::size_t i = 0; i < P.size(); ++i)
    for (int a = 0; a < 3; ++a)
      if (std::fabs(double(v[a][i])) * sim_.dt_ > widest)
        throw Error(fmt::format("particle {} has velocity {} m/s along {}: one step of {} s carries it {:.3g} m, "
                                "farther than the whole domain ({} m) is wide",
                                P.ids()[i], v[a][i], "xyz"[a], sim_.dt_, std::fabs(double(v[a][i])) * sim_.dt_,
                                widest));
}

// A restart after a complete step, asked for by a signal: where the `restart` fix writes its
// files, else PREFIX.STEP.restart in the current directory.
std::string RunLoop::write_restart_now(const char* prefix) {
  std::string path;
  for (const auto& f : sim_.fixes_)
    if (auto written = f->write_restart_now(sim_)) path = *written;
  if (path.empty()) {
    path = fmt::format("{}.{}.restart", prefix, sim_.step_);
    write_restart(sim_, path);
  }
  return path;
}

// Ctrl-C (or a stop requested): the step is complete; flush the fixes' files, save the
// state, stop.
void RunLoop::stop_interrupted(const std::string& reason) {
  for (const auto& f : sim_.fixes_) f->finish(sim_);
  const std::string path = write_restart_now("interrupted");
  const std::string message =
      fmt::format("{} after step {} (t = {} s): wrote restart '{}'", reason, sim_.step_, sim_.time(), path);
  if (view_) view_->run_ends(sim_, "stopped", message);
  throw Interrupted(message, path);
}

// Particles packed at many times the rest density: the solver has failed (a time step too
// large, an unstable setting). Stop before the neighbour lists grow toward N^2 memory.
void RunLoop::check_clumping() const {
  const auto& grid = sim_.grid_;
  std::size_t first = 0;
  while (first < grid.particle_count() && grid.count(first) <= 20 * full_neighborhood_ + 100) ++first;
  throw Error(fmt::format(
      "step {}: the fluid has collapsed into clumps: particle {} has {} neighbours within h, where a particle at "
      "rest density has about {:.0f} (a time step too large for the solver, or an unstable setting such as a "
      "two-sided constraint without wall density)",
      sim_.step_ + 1, sim_.particles_.ids()[first], grid.count(first), full_neighborhood_));
}

// Whether particle i's position or velocity is NaN or infinite (x * 0 is NaN exactly then).
namespace {
bool non_finite(const Particles& P, std::size_t i) {
  const real s = P.x()[i] * 0 + P.y()[i] * 0 + P.z()[i] * 0 + P.vx()[i] * 0 + P.vy()[i] * 0 + P.vz()[i] * 0;
  return s != s;
}
}  // namespace

// The first particle (in memory order) whose position or velocity is NaN or infinite; n if none.
std::size_t RunLoop::first_non_finite() const {
  const auto& P = sim_.particles_;
  return first_particle(P.size(), [&](std::size_t i) { return non_finite(P, i); });
}

std::string RunLoop::blew_up(std::size_t i) const {
  const auto& P = sim_.particles_;
  return fmt::format("the simulation blew up: particle {} has a non-finite position or velocity (position {} {} {}, "
                     "velocity {} {} {})",
                     P.ids()[i], P.x()[i], P.y()[i], P.z()[i], P.vx()[i], P.vy()[i], P.vz()[i]);
}

void RunLoop::check_finite(Stage stage, const Fix& fix) const {
  const std::size_t first = first_non_finite();
  if (first == sim_.particles_.size()) return;
  throw Error(fmt::format("step {}: {} after fix '{}' ({}) in stage {}", sim_.step_ + 1, blew_up(first), fix.id(),
                          fix.style(), stage_name(stage)));
}

// The step's one check, in one pass: every position and velocity finite (a blow-up; the
// first one is named), then every particle inside the domain. Which fix produced a
// non-finite value only a check after every hook can say: the message says how to ask.
void RunLoop::check_end_of_step(std::int64_t step) const {
  const auto& P = sim_.particles_;
  const Domain& domain = sim_.domain_;
  const auto [bad, outside] = first_particles<2>(P.size(), [&](std::size_t i) {
    return std::array<bool, 2>{non_finite(P, i), !domain.contains(P.x()[i], P.y()[i], P.z()[i])};
  });
  if (bad < P.size())
    throw Error(fmt::format("step {}: {} at the end of the step (run it again with --check-every-hook to name the "
                            "fix that produced it)",
                            step, blew_up(bad)));
  if (outside < P.size()) throw Error(fmt::format("step {}: {}", step, sim_.outside_domain(outside)));
}

}  // namespace pbf
