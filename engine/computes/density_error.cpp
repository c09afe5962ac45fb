// density_error: rho/rho0 - 1 over the particles, rho the density the solver uses (as the
// density compute): its average and maximum, and the average compression, the mean of
// max(rho/rho0 - 1, 0) (what a one-sided solver removes).
#include <cmath>
#include <algorithm>

#include "engine/registry/builtin_styles.hpp"
#include "engine/core/parallel.hpp"
#include "engine/distributed/comm.hpp"
#include "engine/core/simulation.hpp"

namespace pbf {

namespace {

class DensityError : public Compute {
 public:
  DensityError(const std::string& id, const Params&) : Compute(id, "density_error") {}
  std::vector<std::string> names() const override { return {"avg", "max", "compression"}; }
  std::vector<std::string> units() const override { return {"-", "-", "-"}; }
  bool runs_distributed() const override { return true; }
  void evaluate(Simulation& sim, std::vector<double>& values) override {
    const real* rho = sim.solver_density();
    const double inv = 1.0 / sim.rest_density();
    const std::size_t n = sim.particles().size();
    const double all = double(sim.global_count());
    const bool ranks = sim.particles().distributed();
    const double avg = deterministic_sum(n, [&](std::size_t i) { return rho[i] * inv - 1; }, ranks) / all;
    const double compression =
        deterministic_sum(n, [&](std::size_t i) { return std::max(rho[i] * inv - 1, 0.0); }, ranks) / all;
    double most = -1;
#pragma omp parallel for reduction(max : most)
    for (std::size_t i = 0; i < n; ++i) most = std::max(most, rho[i] * inv - 1);
    values = {avg, ranks ? comm::max(most) : most, compression};
    if (sim.global_count() == 0) values.assign(3, std::nan(""));  // no fluid: nothing to measure
  }
};

}  // namespace

void register_compute_density_error(StyleRegistry& r) {
  r.add({"density_error", StyleKind::compute,
         "rho/rho0 - 1: avg, max, and compression = mean of max(rho/rho0 - 1, 0)", {}, nullptr,
         make_compute<DensityError>(),
         "`avg`, `max`, `compression` (-, relative to rho0)"});
}

}  // namespace pbf
