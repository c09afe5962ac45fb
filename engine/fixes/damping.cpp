// damping: a zone where velocities relax to zero, so that waves and flows that reach an open
// end or a wave flume's far wall leave without reflecting (DualSPHysics's damping zone). The
// zone starts at the plane through `from` normal to n = (to - from) / L, L = |to - from|, and
// grows to full strength at the plane through `to`, staying full beyond it:
//   s(x) = clamp((x - from) . n / L, 0, 1)
//   v <- v exp(-rate s(x)^2 dt)          (after the velocity update, each step)
// The quadratic ramp makes the zone's start gentle, so that it does not reflect waves itself;
// the exponential makes `rate` a relaxation rate per second whatever the time step (a
// particle held at s for a time T keeps exp(-rate s^2 T) of its velocity). Particles behind
// the `from` plane are untouched, bit for bit.
#include <cmath>

#include <fmt/format.h>

#include "engine/core/error.hpp"
#include "engine/core/parallel.hpp"
#include "engine/core/simulation.hpp"
#include "engine/registry/builtin_styles.hpp"

namespace pbf {

namespace {

class Damping : public Fix {
 public:
  Damping(const std::string& id, const Params& p) : Fix(id, "damping"), rate_(p.real("rate")) {
    const Vec3 from = p.vec3("from"), to = p.vec3("to");
    double length2 = 0;
    for (int a = 0; a < 3; ++a) length2 += (to[a] - from[a]) * (to[a] - from[a]);
    length_ = std::sqrt(length2);
    if (!(length_ > 0))
      throw Error(fmt::format("parameters 'from' and 'to' are the same point ({}, {}, {}): the zone needs a length "
                              "along which the damping grows",
                              from[0], from[1], from[2]));
    for (int a = 0; a < 3; ++a) {
      from_[a] = from[a];
      normal_[a] = (to[a] - from[a]) / length_;
    }
  }

  std::vector<Stage> stages() const override { return {Stage::velocity_post}; }
  bool runs_distributed() const override { return true; }  // each particle on its own

  void velocity_post(Simulation& sim) override {
    auto& P = sim.particles();
    const real *x = P.x(), *y = P.y(), *z = P.z();
    real *vx = P.vx(), *vy = P.vy(), *vz = P.vz();
    const double inv_length = 1 / length_, rate_dt = rate_ * sim.timestep();
    for_particles(P.size(), [&](std::size_t i) {
      const double depth = ((double(x[i]) - from_[0]) * normal_[0] + (double(y[i]) - from_[1]) * normal_[1] +
                            (double(z[i]) - from_[2]) * normal_[2]) *
                           inv_length;
      if (depth <= 0) return;
      const double s = depth < 1 ? depth : 1;
      const real keep = real(std::exp(-rate_dt * s * s));
      vx[i] *= keep;
      vy[i] *= keep;
      vz[i] *= keep;
    });
  }

 private:
  double rate_, length_ = 0;
  double from_[3] = {0, 0, 0}, normal_[3] = {0, 0, 0};
};

}  // namespace

void register_damping(StyleRegistry& r) {
  r.add({"damping",
         StyleKind::fix,
         "a zone where velocities relax to zero (waves and flows leave without reflecting)",
         {ParamSpec{"from", ParamType::Vector3, std::nullopt, "m", "where the zone starts (no damping on its plane)"}
              .magnitude_at_most(1e6),
          ParamSpec{"to", ParamType::Vector3, std::nullopt, "m",
                    "where it is at full strength (and beyond); the zone grows along to - from as the square of "
                    "the distance"}
              .magnitude_at_most(1e6),
          ParamSpec{"rate", ParamType::Real, 10.0, "1/s",
                    "relaxation rate at full strength: velocities keep exp(-rate s^2 t) after a time t at depth s"}
              .above_within(0, 1e6)},
         [](const std::string& id, const Params& p) { return std::make_unique<Damping>(id, p); }, nullptr});
}

}  // namespace pbf
