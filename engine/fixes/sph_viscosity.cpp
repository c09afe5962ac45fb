// sph_viscosity: viscous accelerations of weakly compressible SPH, added to the integrator's
// "acceleration" field in the forces stage (after wcsph, which sets the density):
//   artificial (Monaghan 1992): a_i += -sum_j m_j Pi_ij gradW_ij,
//       Pi_ij = -alpha c0 h mu_ij / rho_ij  where v_ij . x_ij < 0 (approaching), else 0,
//       mu_ij = v_ij . x_ij / (|x_ij|^2 + 0.01 h^2),  rho_ij = (rho_i + rho_j) / 2
//   laplacian (Morris et al. 1997), kinematic viscosity nu, in the form symmetric in i and j
//   (so momentum is conserved; 2 nu m_j / rho_j when the densities are equal):
//       a_i += sum_j nu m_j (1/rho_i + 1/rho_j) v_ij (x_ij . gradW_ij) / (|x_ij|^2 + 0.01 h^2)
// Wendland C2 gradients, as the pressure force.
#include <algorithm>
#include <fmt/format.h>

#include "engine/accelerations.hpp"
#include "engine/error.hpp"
#include "engine/fixes/styles.hpp"
#include "engine/simulation.hpp"

namespace pbf {

namespace {

class SphViscosity : public Fix {
 public:
  SphViscosity(const std::string& id, const Params& p)
      : Fix(id, "sph_viscosity"),
        artificial_(p.string("kind") == "artificial"),
        alpha_(p.real("alpha")),
        nu_(p.real("nu")),
        c0_(p.real("sound_speed")) {
    if (p.string("kind") != "artificial" && p.string("kind") != "laplacian")
      throw Error(fmt::format("parameter 'kind' must be \"artificial\" or \"laplacian\", got \"{}\"", p.string("kind")));
    if (alpha_ < 0 || nu_ < 0 || c0_ < 0) throw Error("'alpha', 'nu' and 'sound_speed' must be >= 0");
  }

  std::vector<Stage> stages() const override { return {Stage::forces}; }
  bool needs_neighbors() const override { return true; }

  void init(Simulation& sim) override {
    require_integrator(sim, "sph_viscosity");
    auto& P = sim.particles();
    accel_ = P.declare({"acceleration", 3, "acceleration the forces stage accumulates for the integrator (m/s^2)", true});
    fields_ = {"acceleration"};
    if (artificial_ && sound_speed(sim) == 0)
      throw Error("the artificial viscosity needs a sound speed: set 'sound_speed' or add a wcsph fix");
  }

  void forces(Simulation& sim) override {
    auto& P = sim.particles();
    const auto& grid = sim.neighbors();
    const Kernels& K = sim.kernels();
    const std::size_t n = P.size();
    // The density wcsph set this step, or the engine's sum without it.
    const auto field = P.find("density");
    const real* rho = field ? P.data(*field) : sim.density().data();
    const real *x = P.x(), *y = P.y(), *z = P.z(), *m = P.mass(), *vx = P.vx(), *vy = P.vy(), *vz = P.vz();
    real *ax = P.data(accel_, 0), *ay = P.data(accel_, 1), *az = P.data(accel_, 2);
    const real h = K.h, eta2 = real(0.01) * h * h, alpha_c_h = real(alpha_ * sound_speed(sim)) * h, nu = real(nu_);
    const bool artificial = artificial_;
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      real a[3] = {0, 0, 0};
      const std::uint32_t* nb = grid.neighbors(i);
      for (std::uint32_t k = 0; k < grid.count(i); ++k) {
        const std::uint32_t j = nb[k];
        const real dx = x[i] - x[j], dy = y[i] - y[j], dz = z[i] - z[j];
        const real ux = vx[i] - vx[j], uy = vy[i] - vy[j], uz = vz[i] - vz[j];
        const real r2 = dx * dx + dy * dy + dz * dz;
        const real g = K.wendland_grad_factor(r2);  // gradW = g x_ij
        if (artificial) {
          const real vr = ux * dx + uy * dy + uz * dz;
          if (vr >= 0) continue;  // separating: no artificial viscosity
          const real mu = vr / (r2 + eta2);
          const real pi_ij = -alpha_c_h * mu / ((rho[i] + rho[j]) / 2);
          const real s = -m[j] * pi_ij * g;
          a[0] += s * dx, a[1] += s * dy, a[2] += s * dz;
        } else {
          const real s = nu * m[j] * (1 / rho[i] + 1 / rho[j]) * g * r2 / (r2 + eta2);
          a[0] += s * ux, a[1] += s * uy, a[2] += s * uz;
        }
      }
      ax[i] += a[0];
      ay[i] += a[1];
      az[i] += a[2];
    }
  }

 private:
  // c0: the parameter, or the largest signal speed of the pipeline (wcsph's sound speed).
  double sound_speed(const Simulation& sim) const {
    double c = c0_;
    if (c == 0)
      for (const auto& f : sim.fixes()) c = std::max(c, f->signal_speed());
    return c;
  }

  bool artificial_;
  double alpha_, nu_, c0_;
  FieldId accel_ = 0;
};

}  // namespace

void register_sph_viscosity(StyleRegistry& r) {
  r.add({"sph_viscosity",
         StyleKind::fix,
         "WCSPH viscosity: Monaghan's artificial viscosity or a Laplacian (physical) viscosity",
         {{"kind", ParamType::String, std::string("artificial"), "", "\"artificial\" (Monaghan) or \"laplacian\" (Morris)"},
          {"alpha", ParamType::Real, 0.1, "", "artificial viscosity coefficient (with h the support radius)"},
          {"nu", ParamType::Real, 1e-6, "m^2/s", "kinematic viscosity of the Laplacian form (water: 1e-6)"},
          {"sound_speed", ParamType::Real, 0.0, "m/s", "c0 of the artificial form; 0: the wcsph fix's sound speed"}},
         [](const std::string& id, const Params& p) { return std::make_unique<SphViscosity>(id, p); }, nullptr});
}

}  // namespace pbf
