// vorticity: vorticity confinement (Fedkiw et al. 2001, as used by Macklin & Mueller 2013),
// putting back rotation that numerical damping removes. SPH volume-weighted forms:
//   omega_i = sum_j (m_j / rho_j) gradW_ij x (v_j - v_i)                (curl of v)
//   eta_i   = sum_j (m_j / rho_j) (|omega_j| - |omega_i|) gradW_ij      (grad |omega|)
//   a_i     = epsilon h |omega_i| (N_i x omega_i),  N = eta / |eta|
// epsilon is dimensionless; the factor h makes the confinement vanish under refinement, as
// Fedkiw's grid form does with the cell size.
#include <cmath>
#include <vector>

#include "engine/core/error.hpp"
#include "engine/registry/builtin_styles.hpp"
#include "engine/core/simulation.hpp"
#include "engine/sph/velocity_curl.hpp"

namespace pbf {

namespace {

class VorticityConfinement : public Fix {
 public:
  VorticityConfinement(const std::string& id, const Params& p) : Fix(id, "vorticity"), epsilon_(p.real("epsilon")) {}

  std::vector<Stage> stages() const override { return {Stage::velocity_post}; }
  bool needs_neighbors() const override { return true; }

  void init(Simulation& sim) override {
    omega_ = sim.particles().declare({"vorticity", 3, "vorticity, curl of the velocity (1/s)", false});
  }

  void velocity_post(Simulation& sim) override {
    const std::vector<real>& rho = sim.summed_density();
    auto& P = sim.particles();
    const auto& grid = sim.neighbors();
    const Kernels& K = sim.kernels();
    const std::size_t n = P.size();
    const real *x = P.x(), *y = P.y(), *z = P.z(), *m = P.mass();
    real *vx = P.vx(), *vy = P.vy(), *vz = P.vz();
    real *wx = P.data(omega_, 0), *wy = P.data(omega_, 1), *wz = P.data(omega_, 2);
    magnitude_.resize(n);
    velocity_curl(sim, rho, wx, wy, wz, magnitude_.data());

    for (auto& c : dv_) c.resize(n);
    const real scale = real(epsilon_ * sim.kernel_radius() * sim.timestep());
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      const real wi = magnitude_[i];
      real eta[3] = {0, 0, 0};
      grid.for_each_neighbor(i, x, y, z, [&](std::uint32_t j, real dx, real dy, real dz, real r2) {
        const real g = m[j] / rho[j] * (magnitude_[j] - wi) * K.grad_factor(r2);
        eta[0] += g * dx;
        eta[1] += g * dy;
        eta[2] += g * dz;
      });
      const real len = std::sqrt(eta[0] * eta[0] + eta[1] * eta[1] + eta[2] * eta[2]);
      real a[3] = {0, 0, 0};
      if (len > real(1e-12) * (wi / K.h + real(1e-30))) {  // no direction where |omega| is flat
        const real s = scale * wi / len;
        a[0] = s * (eta[1] * wz[i] - eta[2] * wy[i]);
        a[1] = s * (eta[2] * wx[i] - eta[0] * wz[i]);
        a[2] = s * (eta[0] * wy[i] - eta[1] * wx[i]);
      }
      dv_[0][i] = a[0];
      dv_[1][i] = a[1];
      dv_[2][i] = a[2];
    }
    real* v[3] = {vx, vy, vz};
    for (int c = 0; c < 3; ++c) {
      real* vc = v[c];
      const real* d = dv_[c].data();
#pragma omp parallel for simd schedule(static)
      for (std::size_t i = 0; i < n; ++i) vc[i] += d[i];
    }
  }

 private:
  double epsilon_;
  FieldId omega_ = 0;
  std::vector<real> magnitude_;  // |omega| of each particle (within a step only)
  std::vector<real> dv_[3];
};

}  // namespace

void register_vorticity(StyleRegistry& r) {
  r.add({"vorticity",
         StyleKind::fix,
         "vorticity confinement, acceleration epsilon h |omega| (N x omega)",
         {ParamSpec{"epsilon", ParamType::Real, 0.05, "",
                    "confinement strength (dimensionless; at 1 a step adds as much rotation as the flow has at the "
                    "scale h)"}
              .within(0, 1)},
         [](const std::string& id, const Params& p) { return std::make_unique<VorticityConfinement>(id, p); },
         nullptr});
}

}  // namespace pbf
