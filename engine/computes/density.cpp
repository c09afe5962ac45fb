// density: the density of every particle (kg/m^3) as the solver uses it: wcsph's own
// density field (summed or integrated), else the SPH sum with walls.
#include <algorithm>
#include <bit>

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
  void evaluate_per_particle(Simulation& sim, std::vector<std::int64_t>& ids, std::vector<double>& values) override {
    const real* rho = sim.solver_density();
    const auto& P = sim.particles();
    // (id, value) pairs of every rank, the value's bits carried as an integer.
    std::vector<std::int64_t> pairs(2 * P.size());
    for (std::size_t i = 0; i < P.size(); ++i) {
      pairs[2 * i] = P.ids()[i];
      pairs[2 * i + 1] = std::bit_cast<std::int64_t>(static_cast<double>(rho[i]));
    }
    if (P.distributed()) pairs = comm::gather_all_varying(pairs);
    std::vector<std::size_t> order(pairs.size() / 2);
    for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return pairs[2 * a] < pairs[2 * b]; });
    ids.resize(order.size());
    values.resize(order.size());
    for (std::size_t k = 0; k < order.size(); ++k) {
      ids[k] = pairs[2 * order[k]];
      values[k] = std::bit_cast<double>(pairs[2 * order[k] + 1]);
    }
  }
};

}  // namespace

void register_compute_density(StyleRegistry& r) {
  r.add({"density", StyleKind::compute, "per-particle density the solver uses (kg/m^3): wcsph's density, else the SPH sum with walls", {}, nullptr,
         make_compute<Density>(),
         "one per particle, the density (kg/m^3)"});
}

}  // namespace pbf
