// front: a percentile of one coordinate (m), a dam-break surge front that one stray
// droplet does not move (the farthest particle would). Along a periodic axis the coordinates
// as they are, not unwrapped: a front that goes through a face comes back at the other side.
#include <algorithm>
#include <cmath>

#include "engine/core/error.hpp"
#include "engine/registry/builtin_styles.hpp"
#include "engine/core/simulation.hpp"
#include "engine/distributed/selection.hpp"

namespace pbf {

namespace {

class Front : public Compute {
 public:
  Front(const std::string& id, const Params& p) : Compute(id, "front"), percentile_(p.real("percentile")) {
    axis_ = p.string("axis")[0] - 'x';
  }
  std::vector<std::string> names() const override { return {"value"}; }
  std::vector<std::string> units() const override { return {"m"}; }
  bool runs_distributed() const override { return true; }  // the percentile of every rank's particles
  void evaluate(Simulation& sim, std::vector<double>& values) override {
    const auto& P = sim.particles();
    if (sim.global_count() == 0) {  // no fluid (not yet in, or all gone): no front
      values = {std::nan("")};
      return;
    }
    const real* c = axis_ == 0 ? P.x() : (axis_ == 1 ? P.y() : P.z());
    std::vector<real> coords(c, c + P.size());
    const auto k = static_cast<std::size_t>(std::floor(percentile_ / 100 * double(sim.global_count() - 1) + 0.5));
    values = {double(nth_smallest(coords, k, P.distributed()))};
  }

 private:
  double percentile_;
  int axis_ = 0;
};

}  // namespace

void register_compute_front(StyleRegistry& r) {
  r.add({"front",
         StyleKind::compute,
         "a high percentile of one coordinate (m), e.g. a dam-break surge front",
         {ParamSpec{"axis", ParamType::String, std::string("x"), "", "the coordinate"}.one_of({"x", "y", "z"}),
          ParamSpec{"percentile", ParamType::Real, 99.0, "%", "percentile of the particles' coordinate"}.within(0, 100)},
         nullptr, make_compute<Front>(),
         "one, the coordinate (m); along a periodic axis of the coordinates as they are, within the domain (a "
         "front that goes through a face comes back at the other side)"});
}

}  // namespace pbf
