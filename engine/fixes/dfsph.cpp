// dfsph: divergence-free SPH (Bender & Koschier, "Divergence-Free Smoothed Particle
// Hydrodynamics", SCA 2015, and TVCG 2017), with its integrator. A step, in the engine's stages
// (docs/design.md, "The step"):
//   predict      x += dt v                       (the velocity the last step's solves left)
//   neighbors    lists at the new positions
//   divergence   rho_i, the solves' factors; the divergence-free solve: v += dt a(p_v), with
//                p_v >= 0 such that the density stops growing,
//                  dt Drho_i/Dt + dt^2 B_i(p_v) = 0    wherever Drho_i/Dt > 0
//   forces       the non-pressure accelerations (gravity, viscosity) into "acceleration"
//   constraints  v += dt (a_np + a_wall), then the constant-density solve: v += dt a(p), with
//                p >= 0 such that the density the velocity would bring is rho0,
//                  rho_i + dt Drho_i/Dt + dt^2 B_i(p) = rho0   wherever it would exceed rho0
// with, for either solve's pressure p and pi_i = p_i / rho_i^2, and w_b = grad(rho_b)_i the
// density gradient of wall b (engine/sph/density_boundary.hpp) at particle i:
//   rho_i     = sum_j m_j W_ij + m_i W(0) + sum_b rho_b(x_i)
//   Drho_i/Dt = sum_j m_j (v_i - v_j) . gradW_ij + 2 sum_b (v_i - v_b) . w_b
//   a_i(p)    = -sum_j m_j (pi_i + pi_j) gradW_ij - 2 pi_i sum_b w_b
//   B_i(p)    = sum_j m_j (a_i - a_j) . gradW_ij + 2 a_i . sum_b w_b
// Each wall is fluid mirrored at its surface, moving at the wall's velocity v_b: the mirror
// approaches as the particle does and pushes back at the particle's pressure, so the wall's
// terms carry a factor 2 (as wcsph's). That mirror's pressure also rises with its depth as
// the fluid's does, p_k = p_i + rho0 g . (x_k - x_i), which adds the walls' support
//   a_wall,i  = -rho0 / rho_i^2 sum_b M_b g,   M_b = sum_k m_k gradW_ik (x) (x_k - x_i)
// (the wall's moment, DensityBoundary::add_moment; a uniform surrounding gives M = rho0 1
// and a_wall = -g). Without it a resting column's bottom particles carry 20% more than the
// hydrostatic pressure, held by the fluid's gradient alone. Its part along the wall counts
// only below the free surface (as far as the particle's last pressure over rho0 |g| reaches),
// and none comes from a wall it would pull the particle towards (a ceiling).
//
// Each solve is a relaxed Jacobi iteration on the pressure (SPlisHSPlasH's form of the
// papers' Algorithms 2 and 3): with the source s_i the density the velocity alone would bring
// (rho_i + dt Drho_i/Dt; rho0 + dt max(Drho_i/Dt, 0) for the divergence) and the residual
//   r_i   = rho0 - s_i - dt^2 B_i(p)
//   pi_i <- max(pi_i - omega r_i / (dt^2 d_i), 0),  d_i = |sum_j m_j gradW_ij + 2 sum_b w_b|^2
//                                                         + sum_j m_j^2 |gradW_ij|^2
// (-dt^2 d_i is dt^2 dB_i/dpi_i: the papers' rho_i / alpha_i; omega = `relaxation`; the masses'
// m_i m_j taken as m_j^2, exact for equal masses). Its error is the mean over the particles of
// |r_i| where p_i > 0 (a pressure that pushes more than it must: a warm start from a step that
// needed more) and max(-r_i, 0) where p_i = 0; it stops when that is at most `error` rho0
// (density) or `divergence_error` rho0 (divergence: the density change over one step), after
// at least min_iterations, and the velocities move by dt a_i of the pressure it reached. A
// particle with less than kSparse of a full neighbourhood (walls counted by their density's
// share) is at a free surface: its divergence is left as it is (the reference's rule, which
// keeps spray from sticking), and it carries no divergence pressure (its factor, over few
// neighbours, is large: a drop near the SPHERIC obstacle took its neighbours' whole push and
// was thrown at 300 m/s). Each solve starts from the pressure the last step ended with
// (warm start; in the fields "dfsph_pressure" and "dfsph_divergence_pressure", so restarts
// continue exactly). The field "pressure" is kappa rho^2 (pi + pi_v): the two solves' pressure,
// times the lattice's gradient norm (engine/sph/mass.hpp; 0.950 at h = 2s), so that its exact
// gradient moves the fluid as the SPH sum does; what probes and dumps read. Loads on solids
// are the momenta the wall terms gave the fluid.
//
// The step's length: a particle the solved velocity carries farther than h in one step meets
// neighbours the solve never saw; the run stops there (cfl with courant <= 0.4 keeps it well
// within).
#include <algorithm>
#include <array>
#include <cmath>
#include <omp.h>
#include <vector>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "engine/core/error.hpp"
#include "engine/core/parallel.hpp"
#include "engine/core/simulation.hpp"
#include "engine/registry/builtin_styles.hpp"
#include "engine/sph/density_boundary.hpp"
#include "engine/sph/mass.hpp"
#include "engine/sph/pair_sums.hpp"

namespace pbf {

namespace {

// A free-surface particle: fewer than this share of a full neighbourhood (the reference's 20
// neighbours of the 33.5 its kernel holds at rest).
constexpr double kSparse = 20.0 / 33.5;
// The farthest a particle may move in one step, in kernel radii (see the top).
constexpr double kMostMove = 2.0;

class DivergenceFreeSph : public Fix {
 public:
  DivergenceFreeSph(const std::string& id, const Params& p)
      : Fix(id, "dfsph"),
        density_{p.real("error"), static_cast<int>(p.integer("min_iterations")),
                 static_cast<int>(p.integer("max_iterations"))},
        divergence_{p.real("divergence_error"), static_cast<int>(p.integer("divergence_min_iterations")),
                    static_cast<int>(p.integer("divergence_max_iterations"))},
        divergence_free_(p.boolean("divergence")),
        warm_start_(p.boolean("warm_start")),
        omega_(p.real("relaxation")) {
    for (const auto& [solve, name] : {std::pair{&density_, ""}, std::pair{&divergence_, "divergence_"}})
      if (solve->min_iterations > solve->max_iterations)
        throw Error(fmt::format("{}min_iterations = {} exceeds {}max_iterations = {}", name, solve->min_iterations, name,
                                solve->max_iterations));
  }

  std::vector<Stage> stages() const override {
    if (divergence_free_) return {Stage::predict, Stage::divergence, Stage::constraints};
    return {Stage::predict, Stage::constraints};
  }
  Role role() const override { return Role::solver; }
  int iterations(Stage stage) const override { return solve_of(stage).max_iterations; }
  bool iterations_done(Stage stage, int) const override { return solve_of(stage).finished; }
  bool needs_neighbors() const override { return true; }
  bool runs_distributed() const override { return true; }  // ghosts' pressures and accelerations refreshed
  Integration integration() const override { return Integration::velocities; }
  std::vector<const char*> exclusive_jobs() const override { return {"time integration", "pressure solver"}; }

  void init(Simulation& sim) override {
    auto& P = sim.particles();
    pressure_ = P.declare({"pressure", 1, "pressure of the step's two solves, density and divergence (Pa)", false});
    density_.pressure = P.declare(
        {"dfsph_pressure", 1, "pressure of dfsph's constant-density solve, its next warm start (Pa)", true});
    divergence_.pressure = P.declare(
        {"dfsph_divergence_pressure", 1, "pressure of dfsph's divergence-free solve, its next warm start (Pa)", true});
    accel_ = P.declare(kAccelerationField);
    gravity_ = {0, 0, 0};
    for (const auto& f : sim.fixes())
      for (int c = 0; c < 3; ++c) gravity_[c] += f->body_acceleration()[c];
    g_norm_ = std::sqrt(gravity_[0] * gravity_[0] + gravity_[1] * gravity_[1] + gravity_[2] * gravity_[2]);
    density_.warned = divergence_.warned = false;
    // What probes and dumps read before the first step: the pressure the restart (or
    // nothing) left.
    kappa_ = real(lattice_gradient_norm(sim.particle_mass(), sim.kernels(), sim.rest_density()));
    const real *p = P.data(density_.pressure), *pv = P.data(divergence_.pressure);
    real* pressure = P.data(pressure_);
    for (std::size_t i = 0; i < P.size(); ++i) pressure[i] = kappa_ * (p[i] + (divergence_free_ ? pv[i] : 0));
  }

  // The drift, x += dt v, with the velocity the last step's solves left (and the step's
  // longest move); the step starts with no non-pressure acceleration (the forces stage adds them).
  void predict(Simulation& sim) override {
    auto& P = sim.particles();
    const real dt = real(sim.timestep());
    real *x = P.x(), *y = P.y(), *z = P.z();
    const real *vx = P.vx(), *vy = P.vy(), *vz = P.vz();
    real *ax = P.data(accel_, 0), *ay = P.data(accel_, 1), *az = P.data(accel_, 2);
    fastest_.assign(static_cast<std::size_t>(omp_get_max_threads()), 0);
    for_blocks(P.size(), [&](std::size_t begin, std::size_t end) {
      real most = 0;  // the block's (as pbf's)
      for (std::size_t i = begin; i < end; ++i) {
        x[i] += dt * vx[i];
        y[i] += dt * vy[i];
        z[i] += dt * vz[i];
        ax[i] = ay[i] = az[i] = 0;
        most = std::max(most, vx[i] * vx[i] + vy[i] * vy[i] + vz[i] * vz[i]);
      }
      real& thread_most = fastest_[static_cast<std::size_t>(omp_get_thread_num())];
      thread_most = std::max(thread_most, most);
    }, kStreamBlock);
    check_step_length(sim, double(*std::max_element(fastest_.begin(), fastest_.end())));
    set_up_ = false;
  }

  void divergence(Simulation& sim, int iteration) override {
    if (iteration == 0) {
      set_up(sim);
      start_solve(sim, divergence_, true);
    }
    iterate(sim, divergence_, iteration, sim.solver_report().divergence);
  }

  void constraint(Simulation& sim, int iteration) override {
    if (iteration == 0) {
      if (!set_up_) set_up(sim);
      apply_accelerations(sim);
      start_solve(sim, density_, false);
    }
    iterate(sim, density_, iteration, sim.solver_report().constraints);
  }

 private:
  // One of the two solves: its tolerance and counts, its warm-start field, and this step's state.
  struct Solve {
    double tolerance;
    int min_iterations, max_iterations;
    FieldId pressure = 0;
    bool finished = false, warned = false;
  };
  const Solve& solve_of(Stage stage) const { return stage == Stage::divergence ? divergence_ : density_; }

  // The density (the engine's sum, which the viscosity reads too), the solves' factors and the
  // walls' gradients at the step's positions (they do not move until its drift): one pass.
  void set_up(Simulation& sim) {
    const std::vector<real>& summed = sim.summed_density();  // first: it may refresh the ghosts
    auto& P = sim.particles();
    const auto& walls = sim.density_boundaries();
    const std::size_t n = P.size();
    factor_.resize(n);
    sparse_.resize(n);
    rho_.assign(summed.begin(), summed.begin() + std::ptrdiff_t(n));
    for (auto& a : hydrostatic_) a.assign(n, 0);
    wall_grad_.resize(3 * walls.size());
    for (auto& g : wall_grad_) g.resize(n);
    const auto& grid = sim.neighbors();
    const real rho0 = real(sim.rest_density());
    const double full = 4.0 / 3.0 * M_PI * std::pow(sim.kernel_radius(), 3) * sim.rest_density() / sim.particle_mass();
    const real sparse_count = real(kSparse * full), full_count = real(full);
    real *sx = sim.scratch(0), *sy = sim.scratch(1), *sz = sim.scratch(2), *squares = sim.scratch(3),
         *fluid = sim.scratch(4);
    const PairInput pairs{grid, P.x(), P.y(), P.z(), P.mass(), sim.common_mass(), sim.kernels(), n};
    for_blocks(n, [&](std::size_t begin, std::size_t end) {
      constraint_sums(pairs, begin, end, 1, fluid, sx, sy, sz, squares);
      for (std::size_t i = begin; i < end; ++i) {
        real w[3] = {0, 0, 0}, wall_rho = 0;  // the walls' density gradient
        for (std::size_t b = 0; b < walls.size(); ++b) {
          real own[3] = {0, 0, 0};
          walls[b]->add_density(sim, P.x()[i], P.y()[i], P.z()[i], i, wall_rho, own);
          for (int c = 0; c < 3; ++c) {
            wall_grad_[3 * b + c][i] = own[c];
            w[c] += own[c];
          }
        }
        if (!walls.empty()) hydrostatic_support(sim, i, rho_[i]);
        // d_i = |S + 2 w|^2 + sum_j m_j^2 |gradW_ij|^2, S = sum_j m_j gradW_ij.
        const real cross = (sx[i] + 2 * w[0]) * (sx[i] + 2 * w[0]) + (sy[i] + 2 * w[1]) * (sy[i] + 2 * w[1]) +
                           (sz[i] + 2 * w[2]) * (sz[i] + 2 * w[2]);
        const real d = cross + squares[i];
        factor_[i] = d > 0 ? 1 / d : 0;
        sparse_[i] = real(grid.count(i)) + full_count * wall_rho / rho0 < sparse_count;
      }
    });
    set_up_ = true;
  }

  // The walls' fluid at the hydrostatic pressure: its push beyond the particle's own pressure,
  // -rho0 / rho_i^2 M_b g for each wall b (M_b its moment, DensityBoundary::add_moment), added
  // to the non-pressure accelerations; none from a wall it would pull the particle towards
  // (a ceiling: the fluid there carries no tension). The wall takes the opposite momentum.
  void hydrostatic_support(Simulation& sim, std::size_t i, real rho_i) {
    const auto& walls = sim.density_boundaries();
    const real q[3] = {sim.particles().x()[i], sim.particles().y()[i], sim.particles().z()[i]};
    const real scale = -real(sim.rest_density()) / (rho_i * rho_i), m_dt = sim.particles().mass()[i] * real(sim.timestep());
    const real g[3] = {real(gravity_[0]), real(gravity_[1]), real(gravity_[2])};
    // The wall's fluid beside the particle rises above it only up to the free surface: the
    // part of the moment along the wall counts as far as the particle's depth (its last
    // pressure over rho0 |g|) reaches through the kernel.
    if (g_norm_ == 0) return;
    const real depth = sim.particles().data(density_.pressure)[i] / real(sim.rest_density() * g_norm_);
    const real along = std::min(real(1), depth / real(sim.kernel_radius()));
    for (std::size_t b = 0; b < walls.size(); ++b) {
      real M[6] = {0, 0, 0, 0, 0, 0};
      walls[b]->add_moment(sim, q, i, along, M);
      const real a[3] = {scale * (M[0] * g[0] + M[3] * g[1] + M[4] * g[2]),
                         scale * (M[3] * g[0] + M[1] * g[1] + M[5] * g[2]),
                         scale * (M[4] * g[0] + M[5] * g[1] + M[2] * g[2])};
      if (a[0] * wall_grad_[3 * b][i] + a[1] * wall_grad_[3 * b + 1][i] + a[2] * wall_grad_[3 * b + 2][i] > 0) continue;
      const real push[3] = {a[0] * m_dt, a[1] * m_dt, a[2] * m_dt};
      walls[b]->record_push(i, push);
      for (int c = 0; c < 3; ++c) hydrostatic_[c][i] += a[c];
    }
  }

  // The density each particle's velocity alone brings over the step (s_i at the top), and the
  // pressure the solve starts from: last step's where the fluid is compressed, else none.
  void start_solve(Simulation& sim, Solve& solve, bool divergence) {
    auto& P = sim.particles();
    const auto& walls = sim.density_boundaries();
    const std::size_t n = P.size();
    source_.resize(n);
    pi_.resize(P.size_with_ghosts());
    pi_next_.resize(P.size_with_ghosts());
    sim.update_ghosts({P.vx(), P.vy(), P.vz()});  // changed since the neighbour stage (solve, forces)
    const real dt = real(sim.timestep()), rho0 = real(sim.rest_density());
    const real *x = P.x(), *y = P.y(), *z = P.z(), *vx = P.vx(), *vy = P.vy(), *vz = P.vz();
    const real* rho = rho_.data();
    const real* last = P.data(solve.pressure);
    const PairInput pairs{sim.neighbors(), x, y, z, P.mass(), sim.common_mass(), sim.kernels(), n};
    const bool warm = warm_start_;
    for_blocks(n, [&](std::size_t begin, std::size_t end) {
      divergence_sums(pairs, begin, end, vx, vy, vz, source_.data());
      for (std::size_t i = begin; i < end; ++i) {
        real rate = source_[i];
        for (std::size_t b = 0; b < walls.size(); ++b) {
          const real gb[3] = {wall_grad_[3 * b][i], wall_grad_[3 * b + 1][i], wall_grad_[3 * b + 2][i]};
          if (gb[0] == 0 && gb[1] == 0 && gb[2] == 0) continue;
          real vb[3] = {0, 0, 0};
          const real q[3] = {x[i], y[i], z[i]};
          walls[b]->wall_velocity(sim, q, vb);
          rate += 2 * ((vx[i] - vb[0]) * gb[0] + (vy[i] - vb[1]) * gb[1] + (vz[i] - vb[2]) * gb[2]);
        }
        if (divergence) rate = sparse_[i] || rate < 0 ? 0 : rate;
        source_[i] = (divergence ? rho0 : rho[i]) + dt * rate;
        pi_[i] = warm ? last[i] / (rho[i] * rho[i]) : 0;
      }
    });
    solve.finished = false;
  }

  // The non-pressure accelerations the forces stage added (gravity, viscosity).
  void apply_accelerations(Simulation& sim) {
    auto& P = sim.particles();
    const real dt = real(sim.timestep());
    real *vx = P.vx(), *vy = P.vy(), *vz = P.vz();
    const real *ax = P.data(accel_, 0), *ay = P.data(accel_, 1), *az = P.data(accel_, 2);
    const real *hx = hydrostatic_[0].data(), *hy = hydrostatic_[1].data(), *hz = hydrostatic_[2].data();
    for_particles(P.size(), [&](std::size_t i) {
      vx[i] += dt * (ax[i] + hx[i]);
      vy[i] += dt * (ay[i] + hy[i]);
      vz[i] += dt * (az[i] + hz[i]);
    });
  }

  // One Jacobi iteration (see the top): the pressure's accelerations, then each particle's
  // residual and new pressure; the velocities move once the residual is within tolerance (or
  // the cap is reached), by the accelerations of the pressure that met it.
  void iterate(Simulation& sim, Solve& solve, int iteration, Simulation::SolverReport::Loop& report) {
    auto& P = sim.particles();
    const auto& walls = sim.density_boundaries();
    const std::size_t n = P.size();
    const bool divergence = &solve == &divergence_;
    const real dt = real(sim.timestep()), rho0 = real(sim.rest_density());
    const real step_factor = real(omega_) / (dt * dt);
    real *ax = sim.scratch(0), *ay = sim.scratch(1), *az = sim.scratch(2);
    const PairInput pairs{sim.neighbors(), P.x(), P.y(), P.z(), P.mass(), sim.common_mass(), sim.kernels(), n};

    accelerations(sim, ax, ay, az);
    const real* pi = pi_.data();
    sim.update_ghosts({ax, ay, az});
    real* change = sim.scratch(3);
    real* next = pi_next_.data();
    ThreadSums<1> excess;
    for_blocks(n, [&](std::size_t begin, std::size_t end) {
      divergence_sums(pairs, begin, end, ax, ay, az, change);
      auto& sum = excess.mine()[0];
      for (std::size_t i = begin; i < end; ++i) {
        real b_i = change[i];
        for (std::size_t b = 0; b < walls.size(); ++b)
          b_i += 2 * (ax[i] * wall_grad_[3 * b][i] + ay[i] * wall_grad_[3 * b + 1][i] + az[i] * wall_grad_[3 * b + 2][i]);
        const real r = rho0 - source_[i] - dt * dt * b_i;
        // The solve's error: a compression left (r < 0), or a pressure that pushes more than
        // it must (r > 0 where p > 0; a warm start from a step that needed more).
        const real violation = pi[i] > 0 ? std::fabs(r) : (r < 0 ? -r : 0);
        if (violation > 0 && !(divergence && sparse_[i])) sum.add(double(violation));
        const real updated = pi[i] - step_factor * r * factor_[i];
        next[i] = updated > 0 && !(divergence && sparse_[i]) ? updated : 0;
      }
    });
    const std::size_t all = sim.global_count();
    const double error = all ? excess.total(P.distributed())[0] / double(all) / double(rho0) : 0;
    report.error = error;
    const int done = iteration + 1;
    const bool reached = error <= solve.tolerance;
    solve.finished = (reached && done >= solve.min_iterations) || done >= solve.max_iterations;
    std::swap(pi_, pi_next_);
    if (!solve.finished) return;
    if (!reached && !solve.warned) {
      solve.warned = true;
      spdlog::warn("fix '{}' ({}): the {} solve stopped at its cap of {} iterations in step {} with the mean {} error "
                   "{:.3g} (tolerance {:.3g}); the run goes on (this is said once per run: raise {}max_iterations, "
                   "or shorten the step)",
                   id(), style(), divergence ? "divergence-free" : "constant-density", solve.max_iterations,
                   sim.step() + 1, divergence ? "divergence" : "density", error, solve.tolerance,
                   divergence ? "divergence_" : "");
    }
    finish_solve(sim, solve, divergence);
  }

  // The accelerations a_i(p) of the pressure pi_ (see the top), in (ax, ay, az): one pass.
  void accelerations(Simulation& sim, real* ax, real* ay, real* az) {
    const auto& P = sim.particles();
    const auto& walls = sim.density_boundaries();
    const std::size_t n = P.size();
    const PairInput pairs{sim.neighbors(), P.x(), P.y(), P.z(), P.mass(), sim.common_mass(), sim.kernels(), n};
    sim.update_ghosts({pi_.data()});
    const real* pi = pi_.data();
    for_blocks(n, [&](std::size_t begin, std::size_t end) {
      constraint_corrections(pairs, begin, end, pi, -1, 0, 1, 1, ax, ay, az);
      for (std::size_t i = begin; i < end; ++i) {
        if (pi[i] == 0) continue;
        for (std::size_t b = 0; b < walls.size(); ++b) {
          ax[i] -= 2 * pi[i] * wall_grad_[3 * b][i];
          ay[i] -= 2 * pi[i] * wall_grad_[3 * b + 1][i];
          az[i] -= 2 * pi[i] * wall_grad_[3 * b + 2][i];
        }
      }
    });
  }

  // The velocities move by the accelerations of the pressure that met the tolerance; the walls
  // take the opposite of their pushes; the pressure is kept for the next step's warm start and
  // for the field "pressure".
  void finish_solve(Simulation& sim, Solve& solve, bool divergence) {
    auto& P = sim.particles();
    const auto& walls = sim.density_boundaries();
    const std::size_t n = P.size();
    const real dt = real(sim.timestep());
    real *ax = sim.scratch(0), *ay = sim.scratch(1), *az = sim.scratch(2);
    accelerations(sim, ax, ay, az);
    const real* m = P.mass();
    real *vx = P.vx(), *vy = P.vy(), *vz = P.vz();
    const real* rho = rho_.data();
    real* kept = P.data(solve.pressure);
    real* pressure = P.data(pressure_);
    const real* other = P.data(divergence_.pressure);
    const real* pi = pi_.data();
    for_blocks(n, [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) {
        vx[i] += dt * ax[i];
        vy[i] += dt * ay[i];
        vz[i] += dt * az[i];
        kept[i] = pi[i] * rho[i] * rho[i];
        if (!divergence) pressure[i] = kappa_ * (kept[i] + (divergence_free_ ? other[i] : 0));
        if (pi[i] == 0) continue;
        for (std::size_t b = 0; b < walls.size(); ++b) {
          const real push[3] = {-2 * pi[i] * wall_grad_[3 * b][i] * m[i] * dt,
                                -2 * pi[i] * wall_grad_[3 * b + 1][i] * m[i] * dt,
                                -2 * pi[i] * wall_grad_[3 * b + 2][i] * m[i] * dt};
          walls[b]->record_push(i, push);
        }
      }
    }, kStreamBlock);
  }

  // Stops the run when the solved velocity carried a particle farther than kMostMove h in the
  // drift; `most`: the largest |v|^2. The fastest particle is named (the first in memory order
  // on a tie).
  void check_step_length(const Simulation& sim, double most) const {
    const double h = sim.kernel_radius(), dt = sim.timestep();
    if (!(most * dt * dt > kMostMove * kMostMove * h * h)) return;
    const auto& P = sim.particles();
    std::size_t fast = 0;
    auto speed2 = [&](std::size_t i) {
      return real(P.vx()[i] * P.vx()[i] + P.vy()[i] * P.vy()[i] + P.vz()[i] * P.vz()[i]);
    };
    while (fast + 1 < P.size() && !(double(speed2(fast)) == most)) ++fast;
    const double speed = std::sqrt(most);
    throw Error(fmt::format(
        "particle {} moved {:.3g} m in one step, {:.3g} h (more than {} h: past neighbours the solve never saw), at "
        "{:.3g} m/s: the time step {} s is beyond DFSPH's CFL bound h / |v| = {:.3g} s (fix 'cfl' with courant = "
        "0.4 keeps every step to 0.4 h / |v|max)",
        P.ids()[fast], speed * dt, speed * dt / h, kMostMove, speed, dt, h / speed));
  }

  Solve density_, divergence_;
  bool divergence_free_, warm_start_;
  double omega_;
  FieldId pressure_ = 0, accel_ = 0;
  bool set_up_ = false;  // this step's factors are computed
  // Within a step: each particle's density, factor 1/d_i, free-surface flag, each wall's density
  // gradient (3 arrays per wall), the solve's source s_i, and the pressure pi (with the ghosts').
  std::vector<real> rho_, factor_, sparse_, source_, pi_, pi_next_;
  std::vector<std::vector<real>> wall_grad_;
  std::vector<real> hydrostatic_[3];  // within a step: the walls' hydrostatic support of each particle
  std::array<double, 3> gravity_{};  // the pipeline's body acceleration (gravity's g), and its size
  double g_norm_ = 0;
  real kappa_ = 1;  // the lattice's gradient norm: the field "pressure" is kappa p (see the top)
  std::vector<real> fastest_;  // each thread's largest |v|^2 in the drift
};

}  // namespace

void register_dfsph(StyleRegistry& r) {
  r.add({"dfsph",
         StyleKind::fix,
         "divergence-free SPH (Bender & Koschier 2015, 2017): a divergence-free and a constant-density pressure solve "
         "on velocities, each to a tolerance, with its integrator",
         {ParamSpec{"error", ParamType::Real, 1e-4, "",
                    "tolerance of the constant-density solve: mean predicted compression, relative to rho0 (1e-4: "
                    "0.01%)"}
              .above_within(0, 1),
          ParamSpec{"divergence_error", ParamType::Real, 1e-3, "",
                    "tolerance of the divergence-free solve: mean density change over one step from the velocity's "
                    "divergence, relative to rho0 (1e-3: 0.1%)"}
              .above_within(0, 1),
          ParamSpec{"min_iterations", ParamType::Integer, std::int64_t{2}, "",
                    "fewest iterations of the constant-density solve a step takes"}
              .within(1, 10000),
          ParamSpec{"max_iterations", ParamType::Integer, std::int64_t{100}, "",
                    "most iterations of the constant-density solve a step takes (then it goes on, and says so once)"}
              .within(1, 10000),
          ParamSpec{"divergence_min_iterations", ParamType::Integer, std::int64_t{1}, "",
                    "fewest iterations of the divergence-free solve a step takes"}
              .within(1, 10000),
          ParamSpec{"divergence_max_iterations", ParamType::Integer, std::int64_t{100}, "",
                    "most iterations of the divergence-free solve a step takes"}
              .within(1, 10000),
          {"divergence", ParamType::Bool, true, "", "run the divergence-free solve (false: the density solve only)"},
          {"warm_start", ParamType::Bool, true, "", "start each solve from the pressure of the last step"},
          ParamSpec{"relaxation", ParamType::Real, 0.5, "", "Jacobi relaxation omega of both solves"}.above_within(0, 1)},
         [](const std::string& id, const Params& p) { return std::make_unique<DivergenceFreeSph>(id, p); }, nullptr});
}

}  // namespace pbf
