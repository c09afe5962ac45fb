// extent: the bounding box of the fluid, min and max of x, y and z (m). Along a periodic axis
// the particles' coordinates as they are: within the domain, but for a particle that crossed a
// face in the last step (it wraps at the next step's start), up to a step's travel beyond it.
#include <algorithm>
#include <cmath>

#include "engine/registry/builtin_styles.hpp"
#include "engine/core/simulation.hpp"
#include "engine/distributed/comm.hpp"

namespace pbf {

namespace {

class Extent : public Compute {
 public:
  Extent(const std::string& id, const Params&) : Compute(id, "extent") {}
  std::vector<std::string> names() const override { return {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"}; }
  std::vector<std::string> units() const override { return {"m", "m", "m", "m", "m", "m"}; }
  bool runs_distributed() const override { return true; }  // over every rank's
  void evaluate(Simulation& sim, std::vector<double>& values) override {
    const auto& P = sim.particles();
    const real* c[3] = {P.x(), P.y(), P.z()};
    values.clear();
    for (int a = 0; a < 3; ++a) {
      double lo = INFINITY, hi = -INFINITY;
      const real* ca = c[a];
#pragma omp parallel for reduction(min : lo) reduction(max : hi)
      for (std::size_t i = 0; i < P.size(); ++i) {
        lo = std::min(lo, double(ca[i]));
        hi = std::max(hi, double(ca[i]));
      }
      values.push_back(lo);
      values.push_back(hi);
    }
    if (P.distributed()) {
      double lows[3] = {values[0], values[2], values[4]}, highs[3] = {values[1], values[3], values[5]};
      comm::min(lows);
      comm::max(highs);
      values = {lows[0], highs[0], lows[1], highs[1], lows[2], highs[2]};
    }
    if (sim.global_count() == 0) values.assign(6, std::nan(""));  // no fluid: no extent
  }
};

}  // namespace

void register_compute_extent(StyleRegistry& r) {
  r.add({"extent", StyleKind::compute, "bounding box of the fluid: xmin, xmax, ymin, ymax, zmin, zmax (m)", {},
         nullptr, make_compute<Extent>(),
         "`xmin`, `xmax`, `ymin`, `ymax`, `zmin`, `zmax` (m); along a periodic axis the coordinates as they are (a "
         "particle that crossed a face in the last step lies up to a step's travel beyond it until the next wraps it)"});
}

}  // namespace pbf
