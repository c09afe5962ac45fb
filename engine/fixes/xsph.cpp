// xsph: XSPH viscosity (Schechter & Bridson 2012, Macklin & Mueller 2013), smoothing each
// velocity toward its neighbours' in the SPH volume-weighted form, so c is dimensionless:
//   v_i += c sum_j (m_j / rho_j) (v_j - v_i) W_ij
#include <vector>

#include "engine/core/error.hpp"
#include "engine/core/parallel.hpp"
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

  // The smoothed velocities are written into scratch arrays that then take the velocities'
  // place: the sums read the neighbours' velocities before any is smoothed, in one pass.
  void velocity_post(Simulation& sim) override {
    const std::vector<real>& volume = sim.summed_volume();
    auto& P = sim.particles();
    const std::size_t n = P.size();
    const real *vx = P.vx(), *vy = P.vy(), *vz = P.vz();
    real *next_x = sim.scratch(0), *next_y = sim.scratch(1), *next_z = sim.scratch(2);
    sim.update_ghosts({P.vx(), P.vy(), P.vz()});
    const PairInput pairs{sim.neighbors(), P.x(), P.y(), P.z(), P.mass(), 0, sim.kernels(), n};
    const real c = real(c_);
    for_blocks(n, [&](std::size_t begin, std::size_t end) {
      smoothing_sums(pairs, begin, end, volume.data(), vx, vy, vz, next_x, next_y, next_z);
      for (std::size_t i = begin; i < end; ++i) {
        next_x[i] = vx[i] + c * next_x[i];
        next_y[i] = vy[i] + c * next_y[i];
        next_z[i] = vz[i] + c * next_z[i];
      }
    });
    for (int k = 0; k < 3; ++k) sim.swap_with_scratch(Particles::kVelocity, k, static_cast<std::size_t>(k));
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
