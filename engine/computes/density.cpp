// density: the density of every particle (kg/m^3) as the solver uses it: wcsph's own
// density field (summed or integrated), else the SPH sum with walls.
#include "engine/registry/builtin_styles.hpp"
#include "engine/core/simulation.hpp"
#include "engine/distributed/comm.hpp"

namespace pbf {

namespace {

class Density : public Compute {
 public:
  Density(const std::string& id, const Params&) : Compute(id, "density") {}
  std::vector<std::string> names() const override { return {}; }
  std::vector<std::string> units() const override { return {}; }  // (its per-particle values: kg/m^3)
  void evaluate(Simulation&, std::vector<double>& values) override { values.clear(); }
  bool per_particle() const override { return true; }
  // In a distributed run every rank gets every particle's value (a table of all of them).
  bool runs_distributed() const override { return true; }
  void evaluate_per_particle(Simulation& sim, std::vector<double>& by_id) override {
    const real* rho = sim.solver_density();
    const auto* ids = sim.particles().ids();
    const std::size_t n = sim.particles().size();
    by_id.assign(sim.global_count(), 0.0);
    for (std::size_t i = 0; i < n; ++i) by_id[static_cast<std::size_t>(ids[i])] = rho[i];
    // Each value is one rank's, the others add 0: the sum is that value, exactly.
    if (sim.particles().distributed()) comm::sum(std::span<double>(by_id));
  }
};

}  // namespace

void register_compute_density(StyleRegistry& r) {
  r.add({"density", StyleKind::compute, "per-particle density the solver uses (kg/m^3): wcsph's density, else the SPH sum with walls", {}, nullptr,
         make_compute<Density>(),
         "one per particle, the density (kg/m^3)"});
}

}  // namespace pbf
