// count: the number of particles.
#include "engine/registry/builtin_styles.hpp"
#include "engine/core/simulation.hpp"

namespace pbf {

namespace {

class Count : public Compute {
 public:
  Count(const std::string& id, const Params&) : Compute(id, "count") {}
  std::vector<std::string> names() const override { return {"value"}; }
  std::vector<std::string> units() const override { return {"-"}; }
  bool runs_distributed() const override { return true; }  // every rank's
  void evaluate(Simulation& sim, std::vector<double>& values) override {
    values = {static_cast<double>(sim.global_count())};
  }
};

}  // namespace

void register_compute_count(StyleRegistry& r) {
  r.add({"count", StyleKind::compute, "number of particles", {}, nullptr, make_compute<Count>(),
         "one, the count (-)"});
}

}  // namespace pbf
