// front: a percentile of one coordinate (m), a dam-break surge front that one stray
// droplet does not move (the farthest particle would).
#include <algorithm>
#include <cmath>

#include "engine/core/error.hpp"
#include "engine/registry/builtin_styles.hpp"
#include "engine/core/simulation.hpp"

namespace pbf {

namespace {

class Front : public Compute {
 public:
  Front(const std::string& id, const Params& p) : Compute(id, "front"), percentile_(p.real("percentile")) {
    const std::string& axis = p.string("axis");
    if (axis != "x" && axis != "y" && axis != "z") throw Error("parameter 'axis' must be \"x\", \"y\" or \"z\"");
    axis_ = axis[0] - 'x';
    if (percentile_ < 0 || percentile_ > 100) throw Error("parameter 'percentile' must be in [0, 100]");
  }
  std::vector<std::string> names() const override { return {"value"}; }
  void evaluate(Simulation& sim, std::vector<double>& values) override {
    const auto& P = sim.particles();
    const real* c = axis_ == 0 ? P.x() : (axis_ == 1 ? P.y() : P.z());
    std::vector<real> coords(c, c + P.size());
    const auto k = static_cast<std::ptrdiff_t>(std::floor(percentile_ / 100 * double(coords.size() - 1) + 0.5));
    std::nth_element(coords.begin(), coords.begin() + k, coords.end());
    values = {double(coords[static_cast<std::size_t>(k)])};
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
         {{"axis", ParamType::String, std::string("x"), "", "coordinate: \"x\", \"y\" or \"z\""},
          {"percentile", ParamType::Real, 99.0, "%", "percentile of the particles' coordinate"}},
         nullptr, make_compute<Front>()});
}

}  // namespace pbf
