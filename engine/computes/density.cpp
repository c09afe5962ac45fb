// Computes over the SPH density (with wall contributions, as the solver sees it):
//   density        per particle, kg/m^3
//   density_error  avg and max of rho/rho0 - 1, and the average compression,
//                  mean of max(rho/rho0 - 1, 0)
#include <algorithm>

#include "engine/fixes/styles.hpp"
#include "engine/parallel.hpp"
#include "engine/simulation.hpp"

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

class DensityError : public Compute {
 public:
  DensityError(const std::string& id, const Params&) : Compute(id, "density_error") {}
  std::vector<std::string> names() const override { return {"avg", "max", "compression"}; }
  void evaluate(Simulation& sim, std::vector<double>& values) override {
    sim.refresh_neighbors();
    const auto& rho = sim.density();
    const double inv = 1.0 / sim.rest_density();
    const std::size_t n = rho.size();
    const double avg = deterministic_sum(n, [&](std::size_t i) { return rho[i] * inv - 1; }) / double(n);
    const double compression =
        deterministic_sum(n, [&](std::size_t i) { return std::max(rho[i] * inv - 1, 0.0); }) / double(n);
    double most = -1;
#pragma omp parallel for reduction(max : most)
    for (std::size_t i = 0; i < n; ++i) most = std::max(most, rho[i] * inv - 1);
    values = {avg, most, compression};
  }
};

}  // namespace

void register_compute_density(StyleRegistry& r) {
  r.add({"density", StyleKind::compute, "per-particle SPH density (kg/m^3), walls included", {}, nullptr,
         [](const std::string& id, const Params& p) { return std::make_unique<Density>(id, p); }});
}

void register_compute_density_error(StyleRegistry& r) {
  r.add({"density_error", StyleKind::compute,
         "rho/rho0 - 1: avg, max, and compression = mean of max(rho/rho0 - 1, 0)", {}, nullptr,
         [](const std::string& id, const Params& p) { return std::make_unique<DensityError>(id, p); }});
}

}  // namespace pbf
