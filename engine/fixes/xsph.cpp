// xsph: XSPH viscosity (Schechter & Bridson 2012, Macklin & Mueller 2013), smoothing each
// velocity toward its neighbours' in the SPH volume-weighted form, so c is dimensionless:
//   v_i += c sum_j (m_j / rho_j) (v_j - v_i) W_ij
#include <vector>

#include "engine/core/error.hpp"
#include "engine/registry/builtin_styles.hpp"
#include "engine/core/simulation.hpp"
#include "engine/sph/pair_sums.hpp"

namespace pbf {

namespace {

class XsphViscosity : public Fix {
 public:
  XsphViscosity(const std::string& id, const Params& p) : Fix(id, "xsph"), c_(p.real("c")) {}

  std::vector<Stage> stages() const override { return {Stage::velocity_post}; }
  bool needs_neighbors() const override { return true; }
  bool runs_distributed() const override { return true; }  // ghosts' velocities refreshed

  void velocity_post(Simulation& sim) override {
    const std::vector<real>& volume = sim.summed_volume();
    auto& P = sim.particles();
    const std::size_t n = P.size();
    real *vx = P.vx(), *vy = P.vy(), *vz = P.vz();
    real *dx = sim.scratch(0), *dy = sim.scratch(1), *dz = sim.scratch(2);
    sim.update_ghosts({vx, vy, vz});
    const PairInput pairs{sim.neighbors(), P.x(), P.y(), P.z(), P.mass(), 0, sim.kernels(), n};
    smoothing_sums(pairs, volume.data(), vx, vy, vz, dx, dy, dz);
    const real c = real(c_);
#pragma omp parallel for simd schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      vx[i] += c * dx[i];
      vy[i] += c * dy[i];
      vz[i] += c * dz[i];
    }
  }

 private:
  double c_;
};

}  // namespace

void register_xsph(StyleRegistry& r) {
  r.add({"xsph",
         StyleKind::fix,
         "XSPH viscosity, v_i += c sum_j (m_j/rho_j) (v_j - v_i) W_ij",
         {ParamSpec{"c", ParamType::Real, 0.01, "", "smoothing coefficient (dimensionless, Macklin & Mueller use 0.01)"}
              .within(0, 1)},
         [](const std::string& id, const Params& p) { return std::make_unique<XsphViscosity>(id, p); }, nullptr});
}

}  // namespace pbf
