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
#include "engine/core/parallel.hpp"
#include "engine/registry/builtin_styles.hpp"
#include "engine/core/simulation.hpp"
#include "engine/sph/pair_sums.hpp"
#include "engine/sph/velocity_curl.hpp"

namespace pbf {

namespace {

class VorticityConfinement : public Fix {
 public:
  VorticityConfinement(const std::string& id, const Params& p) : Fix(id, "vorticity"), epsilon_(p.real("epsilon")) {}

  std::vector<Stage> stages() const override { return {Stage::velocity_post}; }
  bool needs_neighbors() const override { return true; }
  bool runs_distributed() const override { return true; }  // ghosts' velocities and |omega| refreshed

  void init(Simulation& sim) override {
    omega_ = sim.particles().declare({"vorticity", 3, "vorticity, curl of the velocity (1/s)", false});
  }

  void velocity_post(Simulation& sim) override {
    const std::vector<real>& volume = sim.summed_volume();
    auto& P = sim.particles();
    const Kernels& K = sim.kernels();
    const std::size_t n = P.size();
    real *vx = P.vx(), *vy = P.vy(), *vz = P.vz();
    real *wx = P.data(omega_, 0), *wy = P.data(omega_, 1), *wz = P.data(omega_, 2);
    real* magnitude = sim.scratch(3);
    sim.update_ghosts({vx, vy, vz});
    velocity_curl(sim, volume, wx, wy, wz, magnitude);
    sim.update_ghosts({magnitude});

    // eta, the gradient of |omega|; it reads no velocity, so each particle's velocity takes
    // its acceleration as soon as its eta is known, in the same pass.
    real *ex = sim.scratch(0), *ey = sim.scratch(1), *ez = sim.scratch(2);
    const PairInput pairs{sim.neighbors(), P.x(), P.y(), P.z(), P.mass(), 0, K, n};
    const real scale = real(epsilon_ * sim.kernel_radius() * sim.timestep());
    for_blocks(n, [&](std::size_t begin, std::size_t end) {
      gradient_sums(pairs, begin, end, volume.data(), magnitude, ex, ey, ez);
      for (std::size_t i = begin; i < end; ++i) {
        const real wi = magnitude[i];
        const real eta[3] = {ex[i], ey[i], ez[i]};
        const real len = std::sqrt(eta[0] * eta[0] + eta[1] * eta[1] + eta[2] * eta[2]);
        if (!(len > real(1e-12) * (wi / K.h + real(1e-30)))) continue;  // no direction where |omega| is flat
        const real s = scale * wi / len;
        vx[i] += s * (eta[1] * wz[i] - eta[2] * wy[i]);
        vy[i] += s * (eta[2] * wx[i] - eta[0] * wz[i]);
        vz[i] += s * (eta[0] * wy[i] - eta[1] * wx[i]);
      }
    });
  }

 private:
  double epsilon_;
  FieldId omega_ = 0;
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
