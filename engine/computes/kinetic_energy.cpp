// kinetic_energy: the total kinetic energy, sum 1/2 m |v|^2 (J).
#include "engine/registry/builtin_styles.hpp"
#include "engine/core/parallel.hpp"
#include "engine/core/simulation.hpp"

namespace pbf {

namespace {

class KineticEnergy : public Compute {
 public:
  KineticEnergy(const std::string& id, const Params&) : Compute(id, "kinetic_energy") {}
  std::vector<std::string> names() const override { return {"value"}; }
  std::vector<std::string> units() const override { return {"J"}; }
  bool runs_distributed() const override { return true; }
  void evaluate(Simulation& sim, std::vector<double>& values) override {
    const auto& P = sim.particles();
    values = {deterministic_sum(P.size(), [&](std::size_t i) {
      const double vx = P.vx()[i], vy = P.vy()[i], vz = P.vz()[i];
      return 0.5 * P.mass()[i] * (vx * vx + vy * vy + vz * vz);
    }, P.distributed())};
  }
};

}  // namespace

void register_compute_kinetic_energy(StyleRegistry& r) {
  r.add({"kinetic_energy", StyleKind::compute, "total kinetic energy, sum 1/2 m |v|^2 (J)", {}, nullptr,
         make_compute<KineticEnergy>(),
         "one, the energy (J)"});
}

}  // namespace pbf
