// pbf: the density constraint of Macklin & Mueller, "Position Based Fluids" (2013), with
// its integrator: predict positions, iterate the constraint, velocities from positions.
//
//   C_i      = rho_i / rho0 - 1          (one-sided: max(C_i, 0))
//   lambda_i = -omega C_i / (sum_k |grad_k C_i|^2 + epsilon S0)   (omega: `relaxation`)
//   dp_i     = 1/rho0 sum_j m_j (lambda_i + lambda_j + s_corr) gradW_ij  + walls
//   s_corr   = -k (W(r_ij) / W(dq h))^n / S0
//
// W and gradW are one kernel (Wendland C2): with poly6 densities and spiky gradients, as in
// the paper, the corrections are not a projection and a fluid at rest gains energy
// (docs/physics.md, "Kernels"). Linearised on the bulk lattice, one Jacobi iteration
// multiplies a density mode by 1 - omega a(k) with a(k) up to 2.61: omega < 0.77 converges.
//
// S0 is sum_k |grad_k C_i|^2 for a particle at rest inside the initial lattice. Measuring
// epsilon and s_corr in units of S0 makes them scale-free: the same parameters behave the
// same at any resolution and in any unit system (the paper's values assume its units).
//
// Pressure (docs/physics.md, "Pressure in PBF"): a pressure p moves particle i in one step by
// dt^2 a_i = -dt^2/rho0^2 sum_j m_j (p_i + p_j) gradW_ij; the iterations move it by
// 1/rho0 sum_j m_j (lambda_i + lambda_j) gradW_ij each; and the SPH gradient of a
// linear field on the initial lattice is kappa times its gradient (kappa = 0.950 at h = 2s),
// so the pressure whose gradient moves the fluid so is
//   p_i = -kappa rho0 / dt^2 sum_iterations lambda_i / (1 + min(1, rho_wall,i / rho_wall,1))
// The last factor: a wall moves i by lambda_i / rho0 grad(rho_wall) (the wall has no lambda),
// where walls mirroring the pressure would push with 2 p_i, so a particle against a wall
// (rho_wall,1: the wall density of a lattice's first layer) carries twice the multiplier.
// A wall's projection (its contact distance) that moves i by dx after a correction does what
// the wall term would with lambda = rho0 (dx . G) / |G|^2, G the walls' density gradient at
// i: that share of the load is added to p_i the same way.
// Kept in the field "pressure" only when asked for (parameter `pressure`, or a pressure probe).
//
// The step's length: the neighbour lists are built once a step, at the predicted positions,
// so a particle that one step carries farther than kMostMove h has crossed neighbourhoods it
// never saw, and the constraint no longer describes the fluid. The run stops there, naming the
// step, the particle and the step that would do (docs/physics.md, "The largest stable step":
// the dam break stays stable while its particles move up to 1.5 h a step, kStableMove).
#include <algorithm>
#include <cmath>
#include <omp.h>
#include <vector>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "engine/core/error.hpp"
#include "engine/core/parallel.hpp"
#include "engine/distributed/comm.hpp"
#include "engine/registry/builtin_styles.hpp"
#include "engine/sph/compression_watch.hpp"
#include "engine/sph/mass.hpp"
#include "engine/sph/pair_sums.hpp"
#include "engine/sph/point_query.hpp"
#include "engine/core/simulation.hpp"

namespace pbf {

namespace {

constexpr double kMostMove = 2.0;    // in h per step: beyond it, stop (twice the neighbour radius)
constexpr double kStableMove = 1.5;  // in h per step: the most the dam break takes and stays stable

class PositionBasedFluid : public Fix {
 public:
  PositionBasedFluid(const std::string& id, const Params& p)
      : Fix(id, "pbf"),
        iterations_(static_cast<int>(p.integer("iterations"))),
        target_(p.real("error")),
        target_max_(p.real("max_error")),
        min_iterations_(static_cast<int>(p.integer("min_iterations"))),
        max_iterations_(static_cast<int>(p.integer("max_iterations"))),
        epsilon_(p.real("epsilon")),
        k_(p.real("scorr_k")),
        n_(static_cast<int>(p.integer("scorr_n"))),
        dq_(p.real("scorr_dq")),
        one_sided_(p.boolean("one_sided")),
        omega_(p.real("relaxation")),
        pressure_wanted_(p.boolean("pressure")) {
    if (adaptive() && min_iterations_ > max_iterations_)
      throw Error(fmt::format("min_iterations = {} exceeds max_iterations = {}", min_iterations_, max_iterations_));
  }

  std::vector<Stage> stages() const override {
    return {Stage::predict, Stage::constraints, Stage::velocity_update};
  }
  Role role() const override { return Role::solver; }
  int iterations(Stage) const override { return adaptive() ? max_iterations_ : iterations_; }
  bool iterations_done(Stage, int done) const override {
    return adaptive() ? done >= max_iterations_ || (done >= min_iterations_ && reached_) : done >= iterations_;
  }
  bool needs_neighbors() const override { return true; }
  bool runs_distributed() const override { return true; }  // ghosts' positions and multipliers refreshed
  Integration integration() const override { return Integration::positions; }
  std::vector<const char*> exclusive_jobs() const override { return {"time integration"}; }

  void init(Simulation& sim) override {
    auto& P = sim.particles();
    lambda_ = P.declare({"lambda", 1, "PBF constraint multiplier lambda (m^2)", false});
    // The pressure costs a store per particle and iteration and a field: only when wanted.
    keep_pressure_ = pressure_wanted_ || computes_read_pressure(sim);
    if (keep_pressure_) {
      pressure_ = P.declare(
          {"pressure", 1, "pressure from the constraint, -kappa rho0/dt^2 sum of lambda over the step (Pa)", false});
      kappa_ = lattice_gradient_norm(sim.particle_mass(), sim.kernels(), sim.rest_density());
      first_wall_ = lattice_wall_density(sim.particle_mass(), sim.kernels(), sim.rest_density());
      rest_density_ = real(sim.rest_density());
    }
    S0_ = lattice_gradient_sum(sim.particle_mass(), sim.kernels(), sim.rest_density());
    scorr_w_ = sim.kernels().W(real(dq_ * dq_ * sim.kernel_radius() * sim.kernel_radius()));
  }

  void predict(Simulation& sim) override {
    auto& P = sim.particles();
    const std::size_t n = P.size();
    for (auto& c : prev_) c.resize(n);
    const real dt = real(sim.timestep());
    real *x = P.x(), *y = P.y(), *z = P.z(), *px = prev_[0].data(), *py = prev_[1].data(), *pz = prev_[2].data();
    const real *vx = P.vx(), *vy = P.vy(), *vz = P.vz();
    for_particles(n, [&](std::size_t i) {
      px[i] = x[i];
      py[i] = y[i];
      pz[i] = z[i];
      x[i] += dt * vx[i];
      y[i] += dt * vy[i];
      z[i] += dt * vz[i];
    });
  }

  // One iteration in two passes, each one parallel region: the fluid's sums, the walls and
  // the multiplier of each particle; then its correction, with the walls' share, and its
  // corrected position, written into scratch arrays that then take the positions' place (the
  // corrections read the neighbours' positions before any moves: a Jacobi iteration).
  void constraint(Simulation& sim, int iteration) override {
    auto& P = sim.particles();
    const auto& grid = sim.neighbors();
    const Kernels& K = sim.kernels();
    const std::size_t n = P.size();
    const real rho0 = real(sim.rest_density());
    const real inv_rho0 = 1 / rho0;
    const real relax = real(epsilon_ * S0_);
    const real scorr_scale = real(k_ / S0_);
    const real inv_wdq = 1 / scorr_w_;
    const real inv_dt = real(1 / sim.timestep());
    const real* m = P.mass();
    real* lambda = P.data(lambda_);
    real* pressure = keep_pressure_ ? P.data(pressure_) : nullptr;
    const real to_pressure = real(-kappa_) * rho0 * inv_dt * inv_dt, inv_first_wall = real(1 / first_wall_);
    const auto& walls = sim.density_boundaries();
    // A fixed count measures only in its last iteration, for the report.
    const bool measure = adaptive() || iteration + 1 == iterations_;
    if (pressure) wall_share_.resize(n);

    // Scratch arrays are reused as their values are used up, particle by particle: the
    // fluid's gradient (0 to 2) becomes the corrections, then the corrected positions; its
    // density and squared gradients (3, 4) become the first wall's gradient (see
    // wall_gradients).
    real *grad_x = sim.scratch(0), *grad_y = sim.scratch(1), *grad_z = sim.scratch(2), *fluid_rho = sim.scratch(3),
         *grad_sq = sim.scratch(4);
    wall_gradients(sim, walls.size());
    sim.update_ghost_positions();  // moved by the last iteration's corrections and walls
    const real *x = P.x(), *y = P.y(), *z = P.z();
    const PairInput pairs{grid, x, y, z, m, sim.common_mass(), K, n};
    ThreadSums<1> compression;  // of max(rho/rho0 - 1, 0), for the report
    most_.assign(static_cast<std::size_t>(omp_get_max_threads()), 0);
    for_blocks(n, [&](std::size_t begin, std::size_t end) {
      constraint_sums(pairs, begin, end, inv_rho0, fluid_rho, grad_x, grad_y, grad_z, grad_sq);
      auto& compressed = compression.mine()[0];
      real most = 0;  // the block's, kept here: threads writing one cache line would slow each other
      for (std::size_t i = begin; i < end; ++i) {
        const real fluid = fluid_rho[i], squares = grad_sq[i];
        real rho = fluid;
        real gi[3] = {grad_x[i], grad_y[i], grad_z[i]};
        // Each wall's gradient, kept for the correction pass (the positions do not change in between).
        for (std::size_t b = 0; b < walls.size(); ++b) {
          real wall_grad[3] = {0, 0, 0};
          walls[b]->add_density(sim, x[i], y[i], z[i], i, rho, wall_grad);
          for (int c = 0; c < 3; ++c) {
            gi[c] += wall_grad[c] * inv_rho0;
            wall_grad_[3 * b + c][i] = wall_grad[c];
          }
        }
        real C = rho * inv_rho0 - 1;
        if (measure) {
          const real excess = C > 0 ? C : 0;
          compressed.add(double(excess));
          most = excess > most ? excess : most;
        }
        if (one_sided_ && C < 0) C = 0;
        lambda[i] = -real(omega_) * C / (gi[0] * gi[0] + gi[1] * gi[1] + gi[2] * gi[2] + squares + relax);
        if (pressure) {
          // Next to a wall the particle's multiplier does the wall's share too (see the top).
          if (iteration > 0) add_contact_pressure(i, x[i], y[i], z[i], pressure[i], to_pressure);
          const real share = std::min(real(1), (rho - fluid) * inv_first_wall);
          pressure[i] = (iteration == 0 ? 0 : pressure[i]) + to_pressure * lambda[i] / (1 + share);
          wall_share_[i] = share;
        }
      }
      real& thread_most = most_[static_cast<std::size_t>(omp_get_thread_num())];
      thread_most = std::max(thread_most, most);
    });
    if (measure) measure_error(sim, compression.total(P.distributed())[0]);

    // The corrections, in the arrays of the gradients (used up), then the corrected positions.
    real *next_x = grad_x, *next_y = grad_y, *next_z = grad_z;
    sim.update_ghosts({lambda});
    for_blocks(n, [&](std::size_t begin, std::size_t end) {
      constraint_corrections(pairs, begin, end, lambda, inv_rho0, scorr_scale, inv_wdq, n_, next_x, next_y, next_z);
      for (std::size_t i = begin; i < end; ++i) {
        real d[3] = {next_x[i], next_y[i], next_z[i]};
        // A wall's gradient moves only particle i (the wall has no lambda of its own); the
        // wall takes the opposite momentum, m dx / dt.
        for (std::size_t b = 0; b < walls.size(); ++b) {
          real push[3];
          for (int c = 0; c < 3; ++c) {
            const real move = lambda[i] * inv_rho0 * wall_grad_[3 * b + c][i];
            d[c] += move;
            push[c] = m[i] * move * inv_dt;
          }
          walls[b]->record_push(i, push);
        }
        next_x[i] = x[i] + d[0];
        next_y[i] = y[i] + d[1];
        next_z[i] = z[i] + d[2];
      }
    });
    for (int c = 0; c < 3; ++c) sim.swap_with_scratch(Particles::kPosition, c, static_cast<std::size_t>(c));
    if (pressure) {  // where the walls' projections, which come next, start from
      corrected_[0].assign(P.x(), P.x() + n);
      corrected_[1].assign(P.y(), P.y() + n);
      corrected_[2].assign(P.z(), P.z() + n);
    }
  }

  // The velocities from the step's moves, and the step's longest move (one pass).
  void velocity_update(Simulation& sim) override {
    auto& P = sim.particles();
    const std::size_t n = P.size();
    const real inv_dt = real(1 / sim.timestep());
    const real *x = P.x(), *y = P.y(), *z = P.z();
    if (keep_pressure_) {  // the walls' projection after the last correction
      real* pressure = P.data(pressure_);
      const real to_pressure = real(-kappa_) * real(sim.rest_density()) * inv_dt * inv_dt;
      for_particles(n, [&](std::size_t i) { add_contact_pressure(i, x[i], y[i], z[i], pressure[i], to_pressure); });
    }
    real *vx = P.vx(), *vy = P.vy(), *vz = P.vz();
    const real *px = prev_[0].data(), *py = prev_[1].data(), *pz = prev_[2].data();
    std::vector<double>& farthest = farthest_;
    farthest.assign(static_cast<std::size_t>(omp_get_max_threads()), 0);
    for_blocks(n, [&](std::size_t begin, std::size_t end) {
      double most = 0;  // the block's (see constraint)
      for (std::size_t i = begin; i < end; ++i) {
        vx[i] = (x[i] - px[i]) * inv_dt;
        vy[i] = (y[i] - py[i]) * inv_dt;
        vz[i] = (z[i] - pz[i]) * inv_dt;
        most = std::max(most, moved2(P, i));
      }
      double& thread_most = farthest[static_cast<std::size_t>(omp_get_thread_num())];
      thread_most = std::max(thread_most, most);
    }, kStreamBlock);
    check_step_length(sim, *std::max_element(farthest.begin(), farthest.end()));
    if (compression_watch_.due(sim.solver_report().constraints.error))
      spdlog::warn("{}", pbf_compression_warning(fmt::format("fix '{}' ({})", id(), style()), sim.solver_report().constraints.error,
                                                 sim.step() + 1, sim.timestep(), sim.kernel_radius(),
                                                 iterations(Stage::constraints)));
  }

 private:
  // Accuracy-driven iterations: the compression measured in the density pass of an
  // iteration (before its correction), summed in fixed blocks so the count of iterations,
  // and with it every bit of the run, is the same at any thread count. Reported to the
  // `iterations` compute.
  bool adaptive() const { return target_ > 0 || target_max_ > 0; }

  // Where each wall's density gradient waits from the density pass to the corrections: the
  // first wall's in scratch arrays 3 to 5 (free by then), unless the pressure needs it after the
  // iterations (scratch does not outlive a hook); the other walls' in arrays of their own.
  void wall_gradients(Simulation& sim, std::size_t walls) {
    wall_grad_.resize(3 * walls);
    own_wall_grad_.resize(3 * walls);
    for (std::size_t k = 0; k < 3 * walls; ++k) {
      if (k < 3 && !keep_pressure_) {
        wall_grad_[k] = sim.scratch(3 + k);
      } else {
        own_wall_grad_[k].resize(sim.particles().size());
        wall_grad_[k] = own_wall_grad_[k].data();
      }
    }
  }

  // The load a wall's projection carried since the last correction, as the multiplier its
  // density term would have needed (see the top), from the walls' gradient of that iteration.
  void add_contact_pressure(std::size_t i, real x, real y, real z, real& pressure, real to_pressure) const {
    real G[3] = {0, 0, 0};
    for (std::size_t b = 0; b < wall_grad_.size() / 3; ++b)
      for (int c = 0; c < 3; ++c) G[c] += wall_grad_[3 * b + c][i];
    const real G2 = G[0] * G[0] + G[1] * G[1] + G[2] * G[2];
    if (G2 == 0) return;
    const real moved = (x - corrected_[0][i]) * G[0] + (y - corrected_[1][i]) * G[1] + (z - corrected_[2][i]) * G[2];
    pressure += to_pressure * rest_density_ * moved / G2 / (1 + wall_share_[i]);
  }
  // How far particle i moved in this step, squared.
  double moved2(const Particles& P, std::size_t i) const {
    const double dx = double(P.x()[i]) - prev_[0][i], dy = double(P.y()[i]) - prev_[1][i],
                 dz = double(P.z()[i]) - prev_[2][i];
    return dx * dx + dy * dy + dz * dz;
  }

  // Stops the run when a particle moved farther than kMostMove h in this step (see the top);
  // `most`: the largest moved2 of the step. The farthest particle is named, the first in
  // memory order on a tie. A particle that left the domain is the run loop's to name, after
  // this stage: where it went says more (a wall missing) than how far.
  void check_step_length(const Simulation& sim, double most) const {
    const auto& P = sim.particles();
    const std::size_t n = P.size();
    const double h = sim.kernel_radius(), dt = sim.timestep();
    if (!(most > kMostMove * kMostMove * h * h)) return;
    for (std::size_t i = 0; i < n; ++i)
      if (!sim.domain().contains(P.x()[i], P.y()[i], P.z()[i])) return;
    std::size_t far = 0;
    while (moved2(P, far) != most) ++far;
    const double d = std::sqrt(most), speed = d / dt;
    throw Error(fmt::format(
        "particle {} moved {:.3g} m in one step, {:.3g} h (more than {} h: past neighbours the solver never saw), "
        "at {:.3g} m/s: the time step {} s is too large (or a setting unstable, such as relaxation above 0.77); the "
        "largest stable at this speed is about {} h / {:.3g} m/s = {:.3g} s (fix 'cfl' with courant = 0.4 keeps "
        "every step to 0.4 h / |v|max)",
        P.ids()[far], d, d / h, kMostMove, speed, dt, kStableMove, speed, kStableMove * h / speed));
  }

  // The iteration's mean compression (its exact sum over the particles: `compressed`) and
  // largest (the threads' most_), for the report and the adaptive count.
  void measure_error(Simulation& sim, double compressed) {
    const std::size_t all = sim.global_count();
    const bool ranks = sim.particles().distributed();
    const double mean = all ? compressed / double(all) : 0;
    const real local_most = *std::max_element(most_.begin(), most_.end());
    // Over the ranks only when the target reads it: one reduction per iteration otherwise.
    const double most = ranks && target_max_ > 0 ? comm::max(double(local_most)) : double(local_most);
    reached_ = (target_ <= 0 || mean <= target_) && (target_max_ <= 0 || most <= target_max_);
    sim.solver_report().constraints.error = mean;
  }

  int iterations_;
  double target_, target_max_;
  int min_iterations_, max_iterations_;
  CompressionWatch compression_watch_;
  bool reached_ = false;
  double epsilon_, k_;
  int n_;
  double dq_;
  bool one_sided_;
  double omega_;
  bool pressure_wanted_, keep_pressure_ = false;
  double S0_ = 1, kappa_ = 1, first_wall_ = 1;
  real scorr_w_ = 1;
  FieldId lambda_ = 0, pressure_ = 0;
  std::vector<real> prev_[3];  // positions at the start of the step (within a step only)
  std::vector<real> most_;       // each thread's largest compression in an iteration
  std::vector<double> farthest_;  // each thread's longest move (squared) in a step
  std::vector<real> corrected_[3], wall_share_;  // with the pressure: positions after the last correction, wall share
  real rest_density_ = 1000;
  std::vector<real*> wall_grad_;  // each wall's density gradient (3 arrays per wall), within an iteration
  std::vector<std::vector<real>> own_wall_grad_;  // those not in scratch arrays
};

}  // namespace

void register_pbf(StyleRegistry& r) {
  r.add({"pbf",
         StyleKind::fix,
         "Position Based Fluids density constraint and integrator (Macklin & Mueller 2013)",
         {ParamSpec{"iterations", ParamType::Integer, std::int64_t{4}, "", "constraint solver iterations per step"}
              .within(1, 1000),
          ParamSpec{"error", ParamType::Real, 0.0, "",
                    "iterate until the mean compression, mean of max(rho/rho0 - 1, 0), is at most this (0: a fixed "
                    "number of iterations, 'iterations')"}
              .within(0, 1),
          ParamSpec{"max_error", ParamType::Real, 0.0, "",
                    "and until the largest compression is at most this (0: not checked)"}
              .within(0, 1),
          ParamSpec{"min_iterations", ParamType::Integer, std::int64_t{1}, "",
                    "fewest iterations a step takes when 'error' or 'max_error' is set"}
              .within(1, 1000),
          ParamSpec{"max_iterations", ParamType::Integer, std::int64_t{100}, "",
                    "most iterations a step takes when 'error' or 'max_error' is set"}
              .within(1, 1000),
          ParamSpec{"epsilon", ParamType::Real, 0.01, "S0", "relaxation epsilon, relative to S0 (see docs)"}.above(0),
          ParamSpec{"scorr_k", ParamType::Real, 0.0, "",
                    "artificial pressure strength k, as a density error (s_corr is divided by S0; 0: none; 1 pushes "
                    "as hard as a 100% compression)"}
              .within(0, 1),
          ParamSpec{"scorr_n", ParamType::Integer, std::int64_t{4}, "", "artificial pressure exponent n"}.within(1, 16),
          ParamSpec{"scorr_dq", ParamType::Real, 0.2, "h", "artificial pressure reference distance delta q, in units of h"}
              .above_within(0, 1),
          ParamSpec{"relaxation", ParamType::Real, 0.7, "",
                    "Jacobi relaxation omega, scales lambda (below 0.77 the iterations converge on the bulk lattice; "
                    "see docs)"}
              .above_within(0, 1),
          {"one_sided", ParamType::Bool, true, "", "constrain only compression, C = max(rho/rho0 - 1, 0)"},
          {"pressure", ParamType::Bool, false, "",
           "keep the field 'pressure' (Pa) from the multipliers, for dumps (a pressure probe turns it on)"}},
         [](const std::string& id, const Params& p) { return std::make_unique<PositionBasedFluid>(id, p); },
         nullptr});
}

}  // namespace pbf
