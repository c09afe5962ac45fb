#pragma once
// The simulation: the scene (domain, kernel radius, time step, particles), the pipeline of
// fixes and computes a script assembles, and the run loop. It knows nothing of Lua.
// simulation.cpp holds the scene and the pipeline, simulation_neighbors.cpp the neighbour
// lists and the ghosts (other ranks' particles, periodic images), run_loop*.cpp the run.
#include <cstdint>
#include <initializer_list>
#include <memory>
#include <string>
#include <vector>

#include "engine/core/compute.hpp"
#include "engine/sph/density_boundary.hpp"
#include "engine/core/domain.hpp"
#include "engine/core/fix.hpp"
#include "engine/geometry/solid_body.hpp"
#include "engine/sph/kernels.hpp"
#include "engine/sph/neighbor_grid.hpp"
#include "engine/core/particles.hpp"
#include "engine/core/periodic_images.hpp"
#include "engine/core/thermo.hpp"
#include "engine/core/timing.hpp"
#include "engine/output/output_ledger.hpp"
#include "engine/distributed/decomposition.hpp"

namespace pbf {

// Where a simulation's clock stands: time() = time_base + (step - step_base) dt, exact
// multiples of dt since the last change of time step. A restart saves and restores it.
struct Clock {
  std::int64_t step = 0, step_base = 0;
  double time_base = 0;
};

// A fix's state read from a restart, waiting for the script to declare that fix again.
struct SavedFixState {
  std::string id, style;
  std::vector<unsigned char> bytes;
};

// The newest restart written or read: a run that blows up names it.
struct RestartNote {
  std::string path;
  std::int64_t step = -1;
  bool read = false;  // the scene came from it (a continued run)
};

class Simulation {
 public:
  Simulation();
  ~Simulation();

  // --- the scene ---
  Particles& particles() { return particles_; }
  const Particles& particles() const { return particles_; }
  const Domain& domain() const { return domain_; }
  void set_domain(const Domain& domain);
  // Whether a script, scene or restart has set the domain (else it is the unit cube).
  bool domain_set() const { return domain_set_; }
  double kernel_radius() const { return h_; }
  void set_kernel_radius(double h);
  const Kernels& kernels() const { return kernels_; }
  double timestep() const { return dt_; }
  void set_timestep(double dt);
  double rest_density() const { return rest_density_; }
  void set_rest_density(double rho0);
  // Throws when the domain reaches more than 1e6 kernel radii from the origin: positions
  // there cannot resolve h (in single precision they move in steps of 0.1 h), and the
  // neighbour grid's capped cell count would put the whole fluid in one cell; and when a
  // periodic axis is shorter than 2 h.
  void check_scale() const;
  // Moves the particles that crossed a periodic face since the last wrap back by one period
  // (Domain::wrapped): at the top of every step, before migration and reordering, and at a
  // run's start. Nothing to do without a periodic axis.
  void wrap_periodic();
  // Steps between reorderings of particle memory along the grid (0: never).
  void set_reorder_interval(int steps) { reorder_every_ = steps; }

  std::int64_t step() const { return step_; }
  double time() const { return time_base_ + static_cast<double>(step_ - step_base_) * dt_; }
  Clock clock() const { return {step_, step_base_, time_base_}; }
  void set_clock(const Clock& clock);
  int reorder_interval() const { return reorder_every_; }
  // Whether the run loop checks for non-finite positions and velocities after every hook
  // (naming the fix that produced one), instead of once at the end of each step: a
  // debugging aid, one parallel pass more per hook (`pbfengine run --check-every-hook`).
  void set_check_every_hook(bool on) { check_every_hook_ = on; }
  bool check_every_hook() const { return check_every_hook_; }
  // Whether a run in one process checks that every pass refreshes the ghosts' values it reads
  // at neighbours (update_ghosts), as a distributed run needs: each particle gets a copy as a
  // ghost, the neighbour lists name the copies instead of the particles, and every scratch
  // array is filled with NaN before each hook. A pass that reads at neighbours a value it did
  // not refresh then reads NaN (a scratch array) or a stale copy (a field), and the run ends
  // with other bits than the plain run's, or stops at a non-finite value: the mistake shows
  // in one process, without MPI (`pbfengine run --check-ghosts`; tests/test_ghost_refresh.cpp).
  // A debugging aid: the copies double the memory and the refreshes cost a pass each.
  void set_check_ghosts(bool on) { check_ghosts_ = on; }
  bool check_ghosts() const { return check_ghosts_; }

  // --- restarts ---
  // States from a restart: each goes to the fix of the same id (and style) when the script
  // adds it; the first run warns about fixes on one side only.
  void set_saved_states(std::vector<SavedFixState> states, const std::string& source);
  const RestartNote& last_restart() const { return last_restart_; }
  void set_last_restart(RestartNote note) { last_restart_ = std::move(note); }

  // --- the pipeline ---
  void add_fix(std::unique_ptr<Fix> fix);
  void remove_fix(const std::string& id);
  Fix* find_fix(const std::string& id) const;
  const std::vector<std::unique_ptr<Fix>>& fixes() const { return fixes_; }
  // Checks the compute against the scene (Compute::check_scene) when the domain is set.
  void add_compute(std::unique_ptr<Compute> compute);
  void remove_compute(const std::string& id);
  Compute* find_compute(const std::string& id) const;
  const std::vector<std::unique_ptr<Compute>>& computes() const { return computes_; }
  Thermo& thermo() { return thermo_; }
  // The pipeline's queries, one place each:
  // the fix that moves particles through time (pbf, leapfrog), or nullptr;
  const Fix* integrator() const;
  // whether it moves positions in the constraint iterations (pbf; dfsph and leapfrog move them
  // only in predict, so a wall's projection in the constraints' first iteration holds for all);
  bool integrator_moves_positions() const;
  // the fastest signal any fix's physics carries (m/s; 0: none), for time-step control;
  double max_signal_speed() const;
  // the largest kinematic viscosity a fix applies explicitly (m^2/s; 0: none), likewise;
  double max_kinematic_viscosity() const;
  // the mass of a particle of the scene, which sets the lattice spacing its constants depend
  // on (walls' density, PBF's S0): the particles' mean mass; with none (a basin an emitter
  // fills, a tank drained), the mass a fix creates particles with, else the mean mass the
  // scene last had; 0 when there is none of these (a run is refused then). Collective in a
  // distributed run.
  double particle_mass() const;

  // Runs `steps` steps; may be called again, with the pipeline changed in between.
  void run(std::int64_t steps);
  // Runs until the time reaches `time` (within a relative 1e-12): with a time step that
  // changes as the run goes (fix cfl), the number of steps is not known in advance.
  void run_until(double time);
  const TimingTable& last_timing() const { return timing_; }
  // Whether a run is under way (the fixes' hooks are running).
  bool running() const { return running_; }
  // Within a run: every particle's mass when all are equal, else 0 (the pair sums then need
  // not gather masses). Kept up to date when the exchange stage changes the particles.
  real common_mass() const { return run_uniform_mass_; }
  // The files the runs have written (the command line lists them at the end).
  OutputLedger& outputs() { return outputs_; }
  const OutputLedger& outputs() const { return outputs_; }
  // What the run now starting plans (set before any fix's init): about how many steps, and
  // the time it ends at (estimated with the current time step when the run is by steps).
  struct RunPlan {
    double steps = 0, end_time = 0;
  };
  const RunPlan& run_plan() const { return run_plan_; }

  // --- services for fixes and computes ---
  // Neighbour lists of this step's neighbour stage (built from predicted positions).
  const NeighborGrid& neighbors() const { return grid_; }
  // Rebuilds the lists if positions changed since they were built (for measurements).
  void refresh_neighbors();
  // The cells of point measurements (probes, gauges; engine/sph/point_query.hpp): this rank's
  // particles and, in a distributed run, the ghosts at the current positions, binned and
  // ordered by id. Collective in a distributed run.
  const NeighborGrid& point_cells();
  // Whether this rank measures at a point (the rank whose box holds the point's cell; in one
  // process, always): its particles and ghosts cover the point's neighbourhood.
  bool measures_at(double x, double y, double z) const;
  // SPH density with wall contributions, at the current positions over the current lists.
  const std::vector<real>& summed_density();
  // Each particle's volume m / rho over that density (what the velocity sums weigh by).
  const std::vector<real>& summed_volume();
  // Per-particle scratch arrays (k < kScratchArrays), one value per particle: for values a
  // hook computes and uses up before it returns. Their contents are undefined when a hook
  // starts. Shared by all fixes (hooks run one at a time), so that a pipeline holds a few
  // such arrays, not a few per fix: memory per particle is the engine's limit on size.
  static constexpr std::size_t kScratchArrays = 6;
  real* scratch(std::size_t k);
  // Scratch array k and a field's component trade places (Particles::swap_values): a pass
  // that wrote the component's new values into the scratch array makes them the field's.
  void swap_with_scratch(FieldId field, int component, std::size_t k);
  // The density the solver uses, for measurements between steps (computes, dumps): the
  // "density" field of a solver that keeps one (wcsph, summed or integrated), else the SPH
  // sum over freshly built lists. One value per particle, in memory order.
  const real* solver_density();
  // What the solvers' repeated stages did: for each (constraints, divergence), the iterations
  // of the last step, their sum over the steps, and the error its solver measured last (0
  // before the first step); and the steps taken.
  struct SolverReport {
    struct Loop {
      int iterations = 0;
      double error = 0;
      std::int64_t iteration_sum = 0;
    };
    Loop constraints, divergence;
    std::int64_t steps = 0;
  };
  SolverReport& solver_report() { return solver_report_; }
  // --- distributed runs (engine/distributed/decomposition.hpp) ---
  // The particles of all ranks.
  std::size_t global_count() const { return particles_.global_size(); }
  // Puts the particles created since the last placement (each rank's shares of the sources)
  // on the ranks that own their cells, with the neighbour grid's cells for the global count.
  // The run's start does it, and so does the first neighbour search before it. Collective.
  void place_particles();
  // The ghosts' copies of these arrays (one value per particle, ghosts included) from their
  // owners: a pass calls it for the values it reads at neighbours that changed since the
  // neighbour stage. Positions go through update_ghost_positions (images are shifted). A
  // no-op in a run of one process without periodic axes. Collective.
  void update_ghosts(std::initializer_list<real*> arrays);
  // The ghosts' positions, when particles moved since they were last sent. Collective.
  void update_ghost_positions();
  const Decomposition& decomposition() const { return decomposition_; }
  // Fixes that move particles outside the run loop's knowledge call this.
  void positions_changed() { ++positions_version_; }
  const std::vector<DensityBoundary*>& density_boundaries() const { return boundaries_; }
  // The solids of the pipeline, in script order (for outputs that draw them).
  const std::vector<const SolidBody*>& solid_bodies() const { return solids_; }

 private:
  friend class RunLoop;
  void check_inside_domain() const;
  // The message for particle i (in memory order) outside the domain.
  std::string outside_domain(std::size_t i) const;
  void collect_boundaries();
  void restore_saved_state(Fix& fix);
  void warn_unmatched_states();

  Particles particles_;
  Domain domain_;
  bool domain_set_ = false;
  double h_ = 0, dt_ = 0, rest_density_ = 1000;
  mutable double last_mean_mass_ = 0;  // the mean mass when the scene last had particles
  Kernels kernels_{1.0};
  int reorder_every_ = 20;
  bool check_every_hook_ = false;
  bool check_ghosts_ = false;
  std::int64_t step_ = 0, step_base_ = 0;
  double time_base_ = 0;

  std::vector<SavedFixState> saved_states_;
  std::string saved_states_source_;
  std::vector<std::string> fixes_matched_;   // ids that met their saved state (restored or warned)
  bool check_saved_states_ = false;           // warn at the next run about fixes on one side only
  RestartNote last_restart_;
  RunPlan run_plan_;
  SolverReport solver_report_;

  std::vector<std::unique_ptr<Fix>> fixes_;
  std::vector<std::unique_ptr<Compute>> computes_;
  Thermo thermo_;
  TimingTable timing_;
  OutputLedger outputs_;

  NeighborGrid grid_, point_grid_;
  std::uint64_t point_grid_version_ = 0, ghosts_version_ = 0;
  bool lists_valid_ = false;  // false when the ghosts were rebuilt after the lists
  void rebuild_ghosts();      // at the current positions: returns nothing, sets ghost_range_
  // The ghosts of check_ghosts(): a copy of every particle, after the images, then the
  // scratch arrays poisoned.
  void copy_particles_as_ghosts();
  void poison_scratch();
  // Whether the particles have ghosts whose values passes must refresh (a distributed run,
  // periodic images, or check_ghosts()).
  bool has_ghosts() const { return particles_.distributed() || check_ghosts_ || domain_.any_periodic(); }
  // The copies of check_ghosts() there are (the last ghosts: particle i's is copies_first() + i).
  std::size_t copies() const {
    return check_ghosts_ && !particles_.distributed() && particles_.ghosts() > 0 ? particles_.size() : 0;
  }
  std::size_t copies_first() const { return particles_.size_with_ghosts() - copies(); }
  PeriodicImages images_;  // this rank's images of its own particles
  CellRange ghost_range_;
  GridGeometry geometry_;
  Decomposition decomposition_;
  // The grid and lists of this rank's particles (ghosts rebuilt first); the seconds each part took.
  struct ListTimes {
    double ghosts = 0, binning = 0, lists = 0;
  };
  ListTimes bin_and_list();
  void refresh_density(bool with_volume);
  bool running_ = false;     // inside Simulation::run (set by the run loop)
  real run_uniform_mass_ = 0;  // within a run: every particle's mass when all are equal, else 0
  std::uint64_t positions_version_ = 1, grid_version_ = 0, density_version_ = 0, ghost_positions_version_ = 0;
  std::vector<real> density_, volume_;
  std::uint64_t volume_version_ = 0;
  RealArray scratch_[kScratchArrays];
  std::vector<DensityBoundary*> boundaries_;
  std::vector<const SolidBody*> solids_;
};

}  // namespace pbf
