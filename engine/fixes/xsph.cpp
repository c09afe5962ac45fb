// xsph: XSPH viscosity (Schechter & Bridson 2012, Macklin & Mueller 2013), smoothing each
// velocity toward its neighbours' in the SPH volume-weighted form, so c is dimensionless:
//   v_i += c sum_j (m_j / rho_j) (v_j - v_i) W_ij
#include <vector>

#include "engine/core/error.hpp"
#include "engine/registry/builtin_styles.hpp"
#include "engine/core/simulation.hpp"

namespace pbf {

namespace {

class XsphViscosity : public Fix {
 public:
  XsphViscosity(const std::string& id, const Params& p) : Fix(id, "xsph"), c_(p.real("c")) {}

  std::vector<Stage> stages() const override { return {Stage::velocity_post}; }
  bool needs_neighbors() const override { return true; }

  void velocity_post(Simulation& sim) override {
    const std::vector<real>& rho = sim.summed_density();
    auto& P = sim.particles();
    const auto& grid = sim.neighbors();
    const Kernels& K = sim.kernels();
    const std::size_t n = P.size();
    const real *x = P.x(), *y = P.y(), *z = P.z(), *m = P.mass();
    real *vx = P.vx(), *vy = P.vy(), *vz = P.vz();
    const real c = real(c_);
    for (auto& d : dv_) d.resize(n);

#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      real d[3] = {0, 0, 0};
      grid.for_each_neighbor(i, x, y, z, [&](std::uint32_t j, real, real, real, real r2) {
        const real w = m[j] / rho[j] * K.W(r2);
        d[0] += w * (vx[j] - vx[i]);
        d[1] += w * (vy[j] - vy[i]);
        d[2] += w * (vz[j] - vz[i]);
      });
      dv_[0][i] = c * d[0];
      dv_[1][i] = c * d[1];
      dv_[2][i] = c * d[2];
    }
    real* v[3] = {vx, vy, vz};
    for (int a = 0; a < 3; ++a) {
      real* va = v[a];
      const real* d = dv_[a].data();
#pragma omp parallel for simd schedule(static)
      for (std::size_t i = 0; i < n; ++i) va[i] += d[i];
    }
  }

 private:
  double c_;
  std::vector<real> dv_[3];
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
