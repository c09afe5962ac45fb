// speed: the largest and the mean particle speed |v| (m/s).
#include <algorithm>
#include <cmath>

#include "engine/registry/builtin_styles.hpp"
#include "engine/core/parallel.hpp"
#include "engine/distributed/comm.hpp"
#include "engine/core/simulation.hpp"

namespace pbf {

namespace {

class Speed : public Compute {
 public:
  Speed(const std::string& id, const Params&) : Compute(id, "speed") {}
  std::vector<std::string> names() const override { return {"max", "avg"}; }
  std::vector<std::string> units() const override { return {"m/s", "m/s"}; }
  bool runs_distributed() const override { return true; }
  void evaluate(Simulation& sim, std::vector<double>& values) override {
    const auto& P = sim.particles();
    auto speed = [&](std::size_t i) {
      const double vx = P.vx()[i], vy = P.vy()[i], vz = P.vz()[i];
      return std::sqrt(vx * vx + vy * vy + vz * vz);
    };
    double most = 0;
#pragma omp parallel for reduction(max : most)
    for (std::size_t i = 0; i < P.size(); ++i) most = std::max(most, speed(i));
    const bool ranks = P.distributed();
    values = {ranks ? comm::max(most) : most,
              deterministic_sum(P.size(), speed, ranks) / double(sim.global_count())};
    if (sim.global_count() == 0) values.assign(2, std::nan(""));  // no fluid: no speed
  }
};

}  // namespace

void register_compute_speed(StyleRegistry& r) {
  r.add({"speed", StyleKind::compute, "particle speed |v|: max and avg (m/s)", {}, nullptr, make_compute<Speed>(),
         "`max`, `avg` (m/s)"});
}

}  // namespace pbf
