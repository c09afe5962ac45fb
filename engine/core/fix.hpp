#pragma once
// A fix is one style instance in the step pipeline (LAMMPS's word): it names the stages
// it joins and implements a hook for each. The run loop calls and times the hooks; a fix
// never times itself.
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "engine/core/real.hpp"
#include "engine/core/stage.hpp"

namespace pbf {

class Simulation;
class DensityBoundary;
class SolidBody;
class BodyForce;
class ByteWriter;
class ByteReader;
class ParticleFlow;
class RunView;

// Order within a stage: the solver first, then other fixes, then boundaries, then outputs,
// each group in script order. So in each constraint iteration the density correction runs
// before the wall projection, walls correct velocities after the solver has set them, and
// dumps and restarts see the finished step. init() follows the same order, so an output
// finds every field the other fixes declare.
enum class Role { solver = 0, other = 1, boundary = 2, output = 3 };

// What a fix integrates: nothing, positions directly (pbf: predict, correct, velocities
// from the displacement), the "acceleration" field the force styles fill (leapfrog), or
// velocities that its solves correct before the positions follow them (dfsph, which also
// applies the force styles' accelerations).
enum class Integration { none, positions, accelerations, velocities };

// Whether an integrator of this kind applies the "acceleration" field the force styles fill.
inline bool applies_accelerations(Integration kind) {
  return kind == Integration::accelerations || kind == Integration::velocities;
}

class Fix {
 public:
  Fix(std::string id, std::string style) : id_(std::move(id)), style_(std::move(style)) {}
  virtual ~Fix() = default;

  const std::string& id() const { return id_; }
  const std::string& style() const { return style_; }

  virtual std::vector<Stage> stages() const = 0;
  virtual Role role() const { return Role::other; }
  // How many iterations a step may take of a repeated stage (constraints, divergence): the
  // run takes the largest of the stage's fixes (at least 1).
  virtual int iterations(Stage) const { return 0; }
  // After `done` iterations of that stage in this step: whether this fix needs no more. The
  // stage's iterations stop when every fix in it says so (a solver with a tolerance stops early).
  virtual bool iterations_done(Stage stage, int done) const { return done >= iterations(stage); }
  virtual bool needs_neighbors() const { return false; }
  // The fastest signal this fix's physics carries (a weakly compressible solver's sound
  // speed, m/s; 0: none): time-step control keeps dt below h over it.
  virtual double signal_speed() const { return 0; }
  // The kinematic viscosity (m^2/s) the fix applies explicitly, for the viscous limit of
  // time-step control (0: none). A fix that reports one applies the no-slip walls' viscous
  // pull (DensityBoundary::add_no_slip), so those walls leave the touching particles'
  // velocity to it.
  virtual double kinematic_viscosity() const { return 0; }
  // How this fix moves particles through time, if it does (at most one fix per pipeline).
  virtual Integration integration() const { return Integration::none; }
  // Whether this fix adds to the "acceleration" field, which needs an integrator of
  // accelerations (leapfrog) in the pipeline.
  virtual bool adds_accelerations() const { return false; }
  // The acceleration this fix gives every free body (a `solid` with a mass) as well as the
  // fluid: gravity's g. The bodies add up every fix's.
  virtual std::array<double, 3> body_acceleration() const { return {0, 0, 0}; }
  // A force on bodies besides the fluid's and gravity (a `spring`; nullptr: none).
  virtual const BodyForce* body_force() const { return nullptr; }
  // Jobs only one fix of a pipeline may do ("time integration", "pressure solver", "walls at
  // the domain faces", ...): a fix that shares one with a fix already added is refused.
  virtual std::vector<const char*> exclusive_jobs() const { return {}; }
  // Walls that add to the density the solver sees (nullptr: none).
  virtual DensityBoundary* density_boundary() { return nullptr; }
  // Whether this style runs on several MPI ranks (its passes refresh the ghosts they read,
  // its sums are over every rank, its output comes from one); others are refused there.
  virtual bool runs_distributed() const { return false; }
  // A solid the outputs draw (nullptr: none).
  virtual const SolidBody* solid_body() const { return nullptr; }
  // What this fix has let into the scene or out of it (emitter, outflow, open faces), for the
  // `flow` compute (nullptr: it adds and removes no particles).
  virtual const ParticleFlow* particle_flow() const { return nullptr; }
  // The mass of each particle this fix creates during a run (an emitter's; 0: it creates
  // none): a scene that starts empty takes its constants from it (Simulation::particle_mass).
  virtual double created_mass(const Simulation&) const { return 0; }
  // A live view of the run this fix serves (the `view` fix; nullptr: none). The run loop
  // agrees its wishes after every step (engine/core/run_view.hpp).
  virtual RunView* run_view() { return nullptr; }
  // The domain's faces this fix leaves open (the box fix's `open`): x-, x+, y-, y+, z-, z+.
  virtual std::array<bool, 6> open_faces() const { return {}; }
  // Whether this fix removes a particle at q (a sink's region), so that an emitter can refuse
  // an opening a sink would empty as it fills.
  virtual bool removes_at(const real /*q*/[3]) const { return false; }

  // Start of every run, before any fix's init(): a fix may change the scene here (a solid
  // leaves out the fluid created inside it), so every init() sees the particles of the run.
  virtual void prepare_scene(Simulation&) {}
  // Start of every run: declare fields (Particles::declare; a field no fix declares in this
  // round is freed), precompute constants, write initial output.
  virtual void init(Simulation&) {}
  // Start of every run, after the init() of every fix but the outputs, which come after it:
  // the particles created since the last run started (a lattice or a file added between
  // runs; all of them at the first run), by index; and, within a run, after the exchange
  // stage that created some (Simulation::running() then). Their fields hold 0. A fix whose
  // field carries a value from step to step sets theirs to where a fluid at rest starts
  // (wcsph's continuity density: rest density); a field computed before it is read needs
  // nothing. Called on every rank of a distributed run (a rank may have none), so it may be
  // collective.
  virtual void init_new_particles(Simulation&, std::span<const std::uint32_t> /*fresh*/) {}
  // The one point of a step where particles may be added (Particles::add with
  // finish_source, so that every rank count numbers them alike) and removed
  // (Particles::remove): its start, before migration, binning and ghosts, so that the
  // neighbour order, the exact sums and the ghosts' place at the end of every array are as
  // in any other step. Anywhere else a change of the particle set is refused.
  virtual void exchange(Simulation&) {}
  virtual void external_forces(Simulation&) {}
  virtual void predict(Simulation&) {}
  virtual void divergence(Simulation&, int /*iteration*/) {}
  virtual void forces(Simulation&) {}
  virtual void constraint(Simulation&, int /*iteration*/) {}
  virtual void velocity_update(Simulation&) {}
  virtual void velocity_post(Simulation&) {}
  virtual void end_of_step(Simulation&) {}
  // End of every run (flush files).
  virtual void finish(Simulation&) {}

  // State that shapes the future but is no particle field (frame counters, a value carried
  // to the next step, a random generator): saved in restarts and handed back, after a read,
  // to the fix of the same id and style. restore_state must read exactly what save_state wrote.
  virtual void save_state(ByteWriter&) const {}
  // Whether a restart records this fix (a continuation with a different pipeline is warned
  // about); the live view is left out: a run continues the same watched or not.
  virtual bool in_restarts() const { return true; }
  virtual void restore_state(ByteReader&) {}
  // A fix that writes restarts writes one now (on Ctrl-C) and returns its path.
  virtual std::optional<std::string> write_restart_now(Simulation&) { return std::nullopt; }

 private:
  std::string id_, style_;
};

}  // namespace pbf
