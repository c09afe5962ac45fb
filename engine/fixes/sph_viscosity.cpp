// sph_viscosity: viscous accelerations of weakly compressible SPH, added to the integrator's
// "acceleration" field in the forces stage (after wcsph, which sets the density):
//   artificial (Monaghan 1992): a_i += -sum_j m_j Pi_ij gradW_ij,
//       Pi_ij = -alpha c0 h mu_ij / rho_ij  where v_ij . x_ij < 0 (approaching), else 0,
//       mu_ij = v_ij . x_ij / (|x_ij|^2 + 0.01 h^2),  rho_ij = (rho_i + rho_j) / 2
//   laplacian (Morris et al. 1997), kinematic viscosity nu, in the form symmetric in i and j
//   (so momentum is conserved; 2 nu m_j / rho_j when the densities are equal), divided by
//   the sum's lattice factor kappa:
//       a_i += nu / kappa sum_j m_j (1/rho_i + 1/rho_j) v_ij (x_ij . gradW_ij) / (|x_ij|^2 + 0.01 h^2)
//       kappa = -V sum_j g(r_j) r_j^2 z_j^2 / (r_j^2 + 0.01 h^2)   (gradW = g r_vec, V = m / rho0)
//     over the run's rest lattice: the cubic lattice whose spacing gives the particle mass the
//     rest density, at the run's h (engine/sph/mass.hpp, as the walls' deltas are calibrated).
//     On it the sum gives a quadratic field kappa times its Laplacian (0.922 at h = 2s, 0.959 at
//     3s: the lattice sum and the regularisation 0.01 h^2), so without the division a flow the
//     viscosity sets runs 1/kappa fast at every resolution of the same h / s (a Poiseuille
//     flow 8% at h = 2s, docs/validation/poiseuille.md). With it the lattice's viscosity at long
//     waves is nu itself: nu is the viscosity the flow shows. Computed once per run (init).
//     And, from each no-slip wall (a box or solid with no_slip = true and its wall density on),
//       a_i += nu / kappa (1 + rho0 / rho_i) Psi(d) (v_wall - v_i)_t,
//     the same term over the wall's fluid moving as Morris's boundary particles do (the
//     velocity continued linearly through v_wall at the surface; engine/sph/viscous_wall.hpp
//     derives Psi, the tangential part _t and the wall's delta). It is the share of the sum
//     that the lattice sites behind the wall would give, so it takes the same 1 / kappa: a
//     linear shear stays force-free at the wall layers, and a parabola keeps its shape. A
//     solid takes the opposite momentum, m a dt, in its load. A scene without no-slip walls
//     pays nothing for it.
// Wendland C2 gradients, as the pressure force.
#include <algorithm>
#include <fmt/format.h>
#include <vector>

#include "engine/core/error.hpp"
#include "engine/core/parallel.hpp"
#include "engine/registry/builtin_styles.hpp"
#include "engine/core/simulation.hpp"
#include "engine/sph/mass.hpp"

namespace pbf {

namespace {

class SphViscosity : public Fix {
 public:
  SphViscosity(const std::string& id, const Params& p)
      : Fix(id, "sph_viscosity"),
        artificial_(p.string("kind") == "artificial"),
        alpha_(p.real("alpha")),
        nu_(p.real("nu")),
        c0_(p.real("sound_speed")) {}

  std::vector<Stage> stages() const override { return {Stage::forces}; }
  bool needs_neighbors() const override { return true; }
  bool adds_accelerations() const override { return true; }
  // Reads velocities (as the neighbour stage sent them) and the density wcsph refreshed.
  bool runs_distributed() const override { return true; }

  void init(Simulation& sim) override {
    accel_ = sim.particles().declare(kAccelerationField);
    if (artificial_ && sound_speed(sim) == 0)
      throw Error("the artificial viscosity needs a sound speed: set 'sound_speed' or add a wcsph fix");
    no_slip_walls_.clear();
    if (kinematic_viscosity() > 0)
      for (DensityBoundary* w : sim.density_boundaries())
        if (w->no_slip()) no_slip_walls_.push_back(w);
    if (!artificial_) kappa_ = lattice_laplacian(sim.particle_mass(), sim.kernels(), sim.rest_density());
  }

  void forces(Simulation& sim) override {
    auto& P = sim.particles();
    const auto& grid = sim.neighbors();
    const Kernels& K = sim.kernels();
    const std::size_t n = P.size();
    // The density wcsph set this step, or the engine's sum without it.
    const auto field = P.find("density");
    const real* rho = field ? P.data(*field) : sim.summed_density().data();
    sim.update_ghosts({P.vx(), P.vy(), P.vz()});  // a solver may have moved them since the neighbour stage (dfsph)
    const real *x = P.x(), *y = P.y(), *z = P.z(), *m = P.mass(), *vx = P.vx(), *vy = P.vy(), *vz = P.vz();
    real *ax = P.data(accel_, 0), *ay = P.data(accel_, 1), *az = P.data(accel_, 2);
    const real h = K.h, eta2 = real(0.01) * h * h, alpha_c_h = real(alpha_ * sound_speed(sim)) * h;
    const real nu = real(nu_ / kappa_);  // the sum's coefficient (the top)
    const bool artificial = artificial_;
    const real rho0 = real(sim.rest_density()), dt = real(sim.timestep());
    for_particles(n, [&](std::size_t i) {
      real a[3] = {0, 0, 0};
      grid.for_each_neighbor(i, x, y, z, [&](std::uint32_t j, real dx, real dy, real dz, real r2) {
        const real ux = vx[i] - vx[j], uy = vy[i] - vy[j], uz = vz[i] - vz[j];
        const real g = K.grad_factor(r2);  // gradW = g x_ij
        if (artificial) {
          const real vr = ux * dx + uy * dy + uz * dz;
          if (vr >= 0) return;  // separating: no artificial viscosity
          const real mu = vr / (r2 + eta2);
          const real pi_ij = -alpha_c_h * mu / ((rho[i] + rho[j]) / 2);
          const real s = -m[j] * pi_ij * g;
          a[0] += s * dx, a[1] += s * dy, a[2] += s * dz;
        } else {
          const real s = nu * m[j] * (1 / rho[i] + 1 / rho[j]) * g * r2 / (r2 + eta2);
          a[0] += s * ux, a[1] += s * uy, a[2] += s * uz;
        }
      });
      for (DensityBoundary* w : no_slip_walls_) {
        const real q[3] = {x[i], y[i], z[i]}, v[3] = {vx[i], vy[i], vz[i]};
        real pull[3] = {0, 0, 0};
        w->add_no_slip(sim, q, i, v, pull);
        if (pull[0] == 0 && pull[1] == 0 && pull[2] == 0) continue;
        const real c = nu * (1 + rho0 / rho[i]), mdt = m[i] * dt;
        const real push[3] = {c * pull[0] * mdt, c * pull[1] * mdt, c * pull[2] * mdt};
        a[0] += c * pull[0], a[1] += c * pull[1], a[2] += c * pull[2];
        w->record_push(i, push);
      }
      ax[i] += a[0];
      ay[i] += a[1];
      az[i] += a[2];
    });
  }

 private:
  // c0: the parameter, or the largest signal speed of the pipeline (wcsph's sound speed).
  // The Laplacian form's nu; the artificial form's stability is the Courant condition's, whose
  // signal speed c0 it scales with (Monaghan 1992). nu, not the sum's nu / kappa: cfl's step
  // 0.125 (h/2)^2 / nu lets the lattice's fastest mode (the checkerboard) decay by
  // dt nu / kappa lambda_max = 0.81 of itself in a step at h = 2s (0.75 undivided), still
  // below 1: no overshoot, and far from the explicit limit 2.
  double kinematic_viscosity() const override { return artificial_ ? 0 : nu_; }
  double sound_speed(const Simulation& sim) const { return c0_ > 0 ? c0_ : sim.max_signal_speed(); }

  bool artificial_;
  double alpha_, nu_, c0_;
  double kappa_ = 1;  // the Laplacian's lattice factor on this run's rest lattice (the top)
  FieldId accel_ = 0;
  std::vector<DensityBoundary*> no_slip_walls_;  // this run's, for the Laplacian form
};

}  // namespace

void register_sph_viscosity(StyleRegistry& r) {
  r.add({"sph_viscosity",
         StyleKind::fix,
         "WCSPH viscosity: Monaghan's artificial viscosity or a Laplacian (physical) viscosity",
         {ParamSpec{"kind", ParamType::String, std::string("artificial"), "", "artificial (Monaghan) or laplacian (Morris)"}
              .one_of({"artificial", "laplacian"}),
          ParamSpec{"alpha", ParamType::Real, 0.1, "", "artificial viscosity coefficient (with h the support radius)"}
              .within(0, 10),
          ParamSpec{"nu", ParamType::Real, 1e-6, "m^2/s",
                    "kinematic viscosity of the Laplacian form (water: 1e-6, honey: about 1e-2)"}
              .within(0, 1e3),
          ParamSpec{"sound_speed", ParamType::Real, 0.0, "m/s", "c0 of the artificial form; 0: the wcsph fix's sound speed"}
              .within(0, kMostSoundSpeed)},
         [](const std::string& id, const Params& p) { return std::make_unique<SphViscosity>(id, p); }, nullptr});
}

}  // namespace pbf
