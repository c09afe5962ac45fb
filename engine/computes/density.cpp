// density: the SPH density of every particle (kg/m^3), walls included, as the solver
// sees it.
#include "engine/registry/builtin_styles.hpp"
#include "engine/core/simulation.hpp"

namespace pbf {

namespace {

class Density : public Compute {
 public:
  Density(const std::string& id, const Params&) : Compute(id, "density") {}
  std::vector<std::string> names() const override { return {}; }
  void evaluate(Simulation&, std::vector<double>& values) override { values.clear(); }
  bool per_particle() const override { return true; }
  void evaluate_per_particle(Simulation& sim, std::vector<double>& by_id) override {
    sim.refresh_neighbors();
    const auto& rho = sim.density();
    const auto* ids = sim.particles().ids();
    by_id.assign(rho.size(), 0.0);
    for (std::size_t i = 0; i < rho.size(); ++i) by_id[static_cast<std::size_t>(ids[i])] = rho[i];
  }
};

}  // namespace

void register_compute_density(StyleRegistry& r) {
  r.add({"density", StyleKind::compute, "per-particle SPH density (kg/m^3), walls included", {}, nullptr,
         make_compute<Density>()});
}

}  // namespace pbf
