// The run loop (engine/core/run_loop.hpp): stages in order, fixes within a stage by role then
// script order, every hook timed, a blow-up caught at the end of the step that produced it
// (after the hook that did, with --check-every-hook).
#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>
#include <omp.h>
#include <spdlog/spdlog.h>

#include "engine/core/error.hpp"
#include "engine/core/interrupt.hpp"
#include "engine/core/parallel.hpp"
#include "engine/core/run_loop.hpp"
#include "engine/distributed/comm.hpp"
#include "engine/sph/pair_sums.hpp"
#include "engine/sph/separate_coincident.hpp"

namespace pbf {

void Simulation::run(std::int64_t steps) {
  if (steps < 0) throw Error(fmt::format("run: the number of steps must be >= 0, got {}", steps));
  RunLoop(*this).run(steps, 0);
}

void Simulation::run_until(double time) {
  if (!std::isfinite(time)) throw Error(fmt::format("run_until: the end time must be finite, got {}", time));
  RunLoop(*this).run(-1, time);
}

void RunLoop::prepare() {
  auto& P = sim_.particles_;
  // The faces particles may leave through are the walls' fix's (none without one).
  bool open[6] = {false, false, false, false, false, false};
  for (const auto& f : sim_.fixes_) {
    const std::array<bool, 6> faces = f->open_faces();
    for (std::size_t k = 0; k < 6; ++k) open[k] = open[k] || faces[k];
  }
  std::copy(open, open + 6, sim_.domain_.open);
  sim_.wrap_periodic();  // a scene made or read with particles beyond a periodic face
  sim_.check_inside_domain();
  sim_.collect_boundaries();
  sim_.warn_unmatched_states();
  for (const auto& f : sim_.fixes_) f->prepare_scene(sim_);
  if (sim_.particle_mass() == 0) throw Error("run: no particle is left: every one was created inside a solid");

  check_pipeline();
  distribute();
  // Particles that start on top of one another would move as one for ever (no kernel gradient
  // between them): moved apart by a rule of positions and ids before any fix sees them. Only at
  // step 0, the start state: later a run continues a flow (a restart, pbf.run called in a loop)
  // and must go on as one long run would. Only particles that interact can be on top of another.
  if (sim_.step_ == 0 &&
      std::any_of(sim_.fixes_.begin(), sim_.fixes_.end(), [](const auto& f) { return f->needs_neighbors(); }))
    separate_coincident(sim_);
  sim_.run_uniform_mass_ = uniform_mass(P.mass(), P.size(), P.distributed());
  // Every fix declares the fields it uses; the outputs start last, after the fields no fix
  // declared are freed and the new particles' fields are set, so that they see what this run has.
  P.begin_declarations();
  for (Role role : kRoles) {
    if (role == Role::output) {
      P.free_undeclared();
      init_new_particles();
    }
    for (const auto& f : sim_.fixes_) {
      if (f->role() != role) continue;
      try {
        f->init(sim_);
      } catch (const Error& e) {
        if (e.located()) throw;
        throw Error(fmt::format("fix '{}' ({}): {}", f->id(), f->style(), e.what()));
      }
    }
  }
  // The computes against the scene the run has: a domain set after them, solids' maps built.
  for (const auto& c : sim_.computes_) c->check_scene(sim_);
  const double h = sim_.h_;
  full_neighborhood_ = 4.0 / 3.0 * M_PI * h * h * h * sim_.rest_density_ / sim_.particle_mass();

  view_ = nullptr;
  for (const auto& f : sim_.fixes_)
    if (RunView* v = f->run_view()) view_ = v;
  neighbors_ = false;
  for (auto& hooks : hooks_) hooks.clear();
  std::fill(std::begin(most_iterations_), std::end(most_iterations_), 1);
  for (Role role : kRoles)
    for (const auto& f : sim_.fixes_) {
      if (f->role() != role) continue;
      for (Stage s : f->stages()) {
        hooks_[static_cast<int>(s)].push_back({f.get(), 0});
        most_iterations_[static_cast<int>(s)] = std::max(most_iterations_[static_cast<int>(s)], f->iterations(s));
      }
      neighbors_ = neighbors_ || f->needs_neighbors();
    }

  // Timing rows in step order, the engine's own work where it happens.
  timing_ = TimingTable();
  if (sim_.particles_.distributed()) {
    row_migrate_ = timing_.row("communication", "migration to the owning rank");
    row_ghosts_ = timing_.row("communication", "ghosts (halo) at the neighbour stage");
  }
  for (int s = 0; s < kStageCount; ++s) {
    const char* stage = stage_name(static_cast<Stage>(s));
    if (static_cast<Stage>(s) == Stage::neighbors && neighbors_) {
      row_reorder_ = timing_.row(stage, "reorder particles along the grid");
      if (!sim_.particles_.distributed() && sim_.domain_.any_periodic())
        row_ghosts_ = timing_.row(stage, "periodic images (ghosts)");
      row_binning_ = timing_.row(stage, "binning (candidates)");
      row_lists_ = timing_.row(stage, "neighbour lists");
    }
    for (Hook& hook : hooks_[s]) hook.row = timing_.row(stage, fmt::format("{} ({})", hook.fix->id(), hook.fix->style()));
  }
  row_thermo_ = timing_.row("end_of_step", "thermo");
  if (view_) row_view_ = timing_.row("end_of_step", "live view (frames, pictures)");
  row_checks_ = timing_.row("checks", "non-finite values, domain");
}

// The particles created since the last run started (ids from Particles::first_new_id() on) get
// their fields from the fixes that declared them; then every particle counts as started.
void RunLoop::init_new_particles() {
  auto& P = sim_.particles_;
  std::vector<std::uint32_t>& fresh = fresh_;  // kept: an emitter's steps allocate nothing
  fresh.clear();
  if (sim_.running_) {  // the exchange stage appended them: the last ones, in order
    std::size_t first = P.size();
    while (first > 0 && P.ids()[first - 1] >= P.first_new_id()) --first;
    for (std::size_t i = first; i < P.size(); ++i) fresh.push_back(static_cast<std::uint32_t>(i));
  } else {  // (placed on their ranks, they may lie anywhere)
    for (std::size_t i = 0; i < P.size(); ++i)
      if (P.ids()[i] >= P.first_new_id()) fresh.push_back(static_cast<std::uint32_t>(i));
  }
  const auto found = static_cast<std::int64_t>(fresh.size());
  if ((P.distributed() ? comm::sum(found) : found) > 0)
    for (const auto& f : sim_.fixes_)
      if (f->role() != Role::output) f->init_new_particles(sim_, fresh);
  P.settle();
}

// A run on several ranks: the particles created since the last run (each rank's shares of the
// sources) go to the ranks that own their cells. Styles not yet written for it are refused by
// name.
void RunLoop::distribute() {
  if (!sim_.particles_.distributed()) {
    sim_.geometry_ = GridGeometry::of(sim_.domain_, sim_.h_);
    return;
  }
  for (const auto& f : sim_.fixes_)
    if (!f->runs_distributed())
      throw Error(fmt::format("fix '{}' ({}) does not run on several MPI ranks yet; run this scene on one "
                              "(without mpirun)",
                              f->id(), f->style()));
  for (const auto& c : sim_.computes_)
    if (!c->runs_distributed())
      throw Error(fmt::format("compute '{}' ({}) does not run on several MPI ranks yet; run this scene on one "
                              "(without mpirun)",
                              c->id(), c->style()));
  sim_.place_particles();
}

void RunLoop::run(std::int64_t steps, double until) {
  const double start = now();
  // What is missing first, then what is absurd.
  // (A scene with none may run when it had some, or a fix creates them: Simulation::particle_mass.)
  check_masses();
  if (sim_.particle_mass() == 0)
    throw Error("run: there are no particles (create them with pbf.lattice or pbf.read_scene)");
  if (sim_.h_ <= 0) throw Error("run: the kernel radius h is not set (pbf.kernel_radius)");
  if (sim_.dt_ <= 0) throw Error("run: the time step is not set (pbf.timestep)");
  sim_.check_scale();
  plan(steps, until);
  check_start_state();
  prepare();
  // From here on the scene's constants stay as every fix's init left them (summed_density),
  // and the particle set changes only at the exchange stage.
  auto& P = sim_.particles_;
  struct Running {
    Simulation& sim;
    ~Running() {
      sim.running_ = false;
      sim.particles_.freeze(false);
    }
  } running{sim_};
  sim_.running_ = true;
  P.freeze(true);
  sim_.decomposition_.reset_seconds();
  const std::int64_t first = sim_.step_, last = first + steps;
  held_seconds_ = 0;
  if (view_) view_->run_starts(sim_, steps >= 0 ? last : -1, until);  // before thermo's first line
  sim_.thermo_.start_run(sim_);
  const double t0 = sim_.time(), end = until - 1e-12 * std::max(1.0, std::fabs(until));
  auto more = [&] { return steps >= 0 ? sim_.step_ < last : sim_.time() < end; };
  double next_progress = start + 10.0;
  InterruptWatch interrupt;
  while (more()) {
    const double before = sim_.time();
    try {
      step();
      // A run to a time whose step control (cfl) shrinks the step to nothing would never end.
      if (steps < 0 && (!(sim_.time() > before) || (until - sim_.time()) / sim_.dt_ > kMostSteps))
        throw Error(fmt::format("step {}: the time step has shrunk to {} s at t = {} s: reaching t = {} s would take "
                                "{:.3g} more steps",
                                sim_.step_, sim_.dt_, sim_.time(), until, (until - sim_.time()) / sim_.dt_));
    } catch (const Error& e) {
      if (view_) view_->run_ends(sim_, "failed", e.what());
      // A failed step leaves the newest restart valid: say where to continue from (the
      // command line adds how).
      const RestartNote& note = sim_.last_restart();
      if (note.path.empty()) throw;
      throw Error(fmt::format("{}; the last restart is '{}' (step {})", e.what(), note.path, note.step), e.located());
    }
    after_step();
    if (now() >= next_progress) {
      const double elapsed = now() - start - held_seconds_;
      const double done = steps >= 0 ? static_cast<double>(sim_.step_ - first) / static_cast<double>(steps)
                                     : (sim_.time() - t0) / (until - t0);
      spdlog::info("progress: step {}, t = {:.6g} s ({:.0f}%), {:.1f} steps/s, about {:.0f} s left", sim_.step_,
                   sim_.time(), 100.0 * done, static_cast<double>(sim_.step_ - first) / elapsed,
                   elapsed * (1 - done) / std::max(done, 1e-9));
      next_progress = now() + 10.0;
    }
  }
  for (const auto& f : sim_.fixes_) f->finish(sim_);
  if (view_) view_->run_ends(sim_, "finished", "");
  if (!P.distributed() && P.ghosts() > 0) {  // between runs the particles have no images or copies
    P.drop_ghosts();
    sim_.lists_valid_ = false;
  }
  timing_.wall_seconds = now() - start - held_seconds_;
  timing_.steps = sim_.step_ - first;
  timing_.particles = sim_.global_count();
  if (sim_.particles_.distributed()) {
    const auto& load = sim_.decomposition_.load();
    timing_.ranks = comm::ranks();
    timing_.load_least = load.least;
    timing_.load_mean = load.mean;
    timing_.load_most = load.most;
    timing_.communication_seconds = sim_.decomposition_.seconds();
    timing_.ghosts_mean = comm::sum(std::int64_t(sim_.decomposition_.ghosts_mean() + 0.5)) / double(comm::ranks());
    timing_.communication_least = comm::min(timing_.communication_seconds);
    timing_.communication_most = comm::max(timing_.communication_seconds);
  }
  timing_.neighbor_mean = neighbor_builds_ ? neighbor_mean_sum_ / static_cast<double>(neighbor_builds_) : 0;
  spdlog::info("{}", timing_.format());
}

void RunLoop::step() {
  auto& P = sim_.particles_;
  const std::int64_t number = sim_.step_ + 1;  // the step being computed
  sim_.wrap_periodic();  // particles that crossed a periodic face come back by a period
  if (!hooks_[static_cast<int>(Stage::exchange)].empty()) exchange();
  if (P.distributed()) {  // particles that left this rank's box go to their owners
    const double t0 = now();
    sim_.decomposition_.migrate(P, sim_.geometry_);
    sim_.positions_changed();
    timing_.add(row_migrate_, now() - t0);
  } else if (P.ghosts() > 0) {  // images and copies, made again at the neighbour stage
    P.drop_ghosts();
    sim_.lists_valid_ = false;
  }
  if (neighbors_ && sim_.reorder_every_ > 0 && sim_.step_ % sim_.reorder_every_ == 0) {
    // Neighbours near in memory: particles in grid-cell order, by id within a cell, so that
    // memory order, and with it every neighbour list, depends on positions and ids only.
    const double t0 = now();
    sim_.grid_.bin(P.x(), P.y(), P.z(), P.size(), sim_.geometry_, cells_holding(P, sim_.geometry_), P.ids());
    P.permute(sim_.grid_.sorted_order(), &sim_.scratch_[0]);
    sim_.positions_changed();
    timing_.add(row_reorder_, now() - t0);
  }
  run_stage(Stage::external_forces);
  run_stage(Stage::predict);
  if (neighbors_) {
    const Simulation::ListTimes times = sim_.bin_and_list();
    if (P.distributed() || sim_.domain_.any_periodic()) timing_.add(row_ghosts_, times.ghosts);
    timing_.add(row_binning_, times.binning);
    timing_.add(row_lists_, times.lists);
    neighbor_mean_sum_ += sim_.grid_.mean_neighbors();
    ++neighbor_builds_;
    const std::uint32_t most = sim_.grid_.max_neighbors();
    timing_.neighbor_max = std::max(timing_.neighbor_max, most);
    if (most > 20 * full_neighborhood_ + 100) check_clumping();
  }
  auto& report = sim_.solver_report_;
  if (!hooks_[static_cast<int>(Stage::divergence)].empty()) iterate(Stage::divergence, report.divergence);
  run_stage(Stage::forces);
  iterate(Stage::constraints, report.constraints);
  ++report.steps;
  run_stage(Stage::velocity_update);
  run_stage(Stage::velocity_post);

  ++sim_.step_;
  const double t0 = now();
  check_end_of_step(number);
  timing_.add(row_checks_, now() - t0);
  run_stage(Stage::end_of_step);
  const double t1 = now();
  sim_.thermo_.end_of_step(sim_);
  timing_.add(row_thermo_, now() - t1);
}

void RunLoop::after_step() {
  InterruptWatch::Requests signals = InterruptWatch::requested(view_ ? view_->wishes() : ViewWishes{});
  auto held = [&] { return signals.view.pause > 0 && signals.view.step == 0 && !signals.stop; };
  if (view_) {
    const double t0 = now();
    view_->act(sim_, signals.view, held());
    timing_.add(row_view_, now() - t0);
  }
  // Held by the view: every rank asks again, in the same reduction, until a viewer resumes,
  // steps or stops the run (or a signal stops it).
  const double hold_start = now();
  for (;;) {
    if (signals.stop) stop_interrupted(signals.reason);
    if (signals.restart) {
      const std::string path = write_restart_now("signal");
      spdlog::info("SIGUSR1: wrote restart '{}' after step {} (t = {} s); the run goes on", path, sim_.step_,
                   sim_.time());
    }
    if (!held()) break;
    view_->wait(0.05);
    signals = InterruptWatch::requested(view_->wishes());
    view_->act(sim_, signals.view, held());
  }
  held_seconds_ += now() - hold_start;
}

// A repeated stage: its hooks, in order, until every one says it is done or the largest
// count a fix allows is reached.
void RunLoop::iterate(Stage stage, Simulation::SolverReport::Loop& report) {
  const auto& hooks = hooks_[static_cast<int>(stage)];
  int iterations = 0;
  while (iterations < most_iterations_[static_cast<int>(stage)]) {
    run_stage(stage, iterations);
    ++iterations;
    bool done = true;
    for (const Hook& hook : hooks) done = done && hook.fix->iterations_done(stage, iterations);
    if (done) break;
  }
  report.iterations = iterations;
  report.iteration_sum += iterations;
}

// Fixes add and remove particles; the new ones get their fields from the fixes that declare
// them, and what a run keeps of the particle set (the common mass) follows it.
void RunLoop::exchange() {
  auto& P = sim_.particles_;
  const std::size_t count = P.global_size();
  const std::int64_t next_id = P.next_id();
  P.freeze(false);
  run_stage(Stage::exchange);
  P.freeze(true);
  if (P.next_id() == next_id && P.global_size() == count) return;
  if (P.next_id() != next_id) init_new_particles();
  sim_.run_uniform_mass_ = uniform_mass(P.mass(), P.size(), P.distributed());
  sim_.positions_changed();
}

void RunLoop::run_stage(Stage stage, int iteration) {
  for (const Hook& hook : hooks_[static_cast<int>(stage)]) {
    if (sim_.check_ghosts_) sim_.poison_scratch();  // undefined when a hook starts: NaN
    const double t0 = now();
    call(stage, *hook.fix, iteration);
    const double t1 = now();
    timing_.add(hook.row, t1 - t0);
    if (stage == Stage::predict || stage == Stage::constraints || stage == Stage::velocity_update)  // positions moved
      sim_.positions_changed();
    if (sim_.check_every_hook_ && stage != Stage::end_of_step) {
      check_finite(stage, *hook.fix);
      timing_.add(row_checks_, now() - t1);
    }
  }
}

void RunLoop::call(Stage stage, Fix& fix, int iteration) {
  try {
    switch (stage) {
      case Stage::exchange: fix.exchange(sim_); break;
      case Stage::external_forces: fix.external_forces(sim_); break;
      case Stage::predict: fix.predict(sim_); break;
      case Stage::neighbors: break;
      case Stage::divergence: fix.divergence(sim_, iteration); break;
      case Stage::forces: fix.forces(sim_); break;
      case Stage::constraints: fix.constraint(sim_, iteration); break;
      case Stage::velocity_update: fix.velocity_update(sim_); break;
      case Stage::velocity_post: fix.velocity_post(sim_); break;
      case Stage::end_of_step: fix.end_of_step(sim_); break;
    }
  } catch (const Error& e) {
    if (e.located()) throw;
    throw Error(fmt::format("step {}: fix '{}' ({}): {}", sim_.step_ + (stage == Stage::end_of_step ? 0 : 1), fix.id(),
                            fix.style(), e.what()));
  }
}

}  // namespace pbf
