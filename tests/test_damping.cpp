// The damping zone (engine/fixes/damping.cpp): a particle at depth s into the zone keeps
// exp(-rate s^2 t) of its velocity after a time t, whatever the time step; one outside it keeps
// its velocity bit for bit. Particles under leapfrog alone (no forces: the
// velocity changes only in the zone) move across the zone's axis, so that each keeps its depth.
// Bound: each step rounds the kept factor and the product (2 u), N steps 2 N u relative, and
// the exponent's rounding of s^2 (3 u of rate t s^2 <= 3 u).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/core/error.hpp"
#include "engine/core/simulation.hpp"
#include "engine/registry/style_registry.hpp"
#include "engine/sph/lattice.hpp"
#include "test_util.hpp"

using namespace pbf;

namespace {

// A row of particles along x, 0.1 m apart, moving at 1 m/s along y (no pair force acts on them);
// the zone from x = 0.3 to 0.7 at `rate`.
void row(Simulation& sim, double dt, double rate) {
  sim.set_domain(Domain{{0, 0, 0}, {1, 1, 0.1}});
  sim.set_kernel_radius(0.2);  // (no pair force in the pipeline)
  sim.set_timestep(dt);
  const double lo[3] = {0, 0.2, 0}, hi[3] = {1, 0.3, 0.1}, v[3] = {0, 1, 0};  // sites at x = 0.05, 0.15, ...
  add_lattice(sim, lo, hi, 0.1, v);
  const auto& styles = StyleRegistry::builtin();
  sim.add_fix(styles.make_fix("integrator", "leapfrog", {}));
  sim.add_fix(styles.make_fix("zone", "damping", {{"from", Vec3{0.3, 0, 0}}, {"to", Vec3{0.7, 0, 0}}, {"rate", rate}}));
}

}  // namespace

TEST(Damping, VelocitiesRelaxAtTheRateForTheirDepthWhateverTheStep) {
  const double rate = 5, t = 0.2;
  for (const double dt : {1e-3, 4e-3}) {
    Simulation sim;
    row(sim, dt, rate);
    const auto steps = static_cast<std::int64_t>(std::lround(t / dt));
    sim.run(steps);
    const auto& P = sim.particles();
    ASSERT_EQ(P.size(), 10u);
    for (std::size_t i = 0; i < P.size(); ++i) {
      const double x = P.x()[i], depth = std::clamp((x - 0.3) / 0.4, 0.0, 1.0);
      const std::string what = "dt " + std::to_string(dt) + ", particle at x = " + std::to_string(x);
      if (depth == 0) {
        EXPECT_EQ(P.vy()[i], real(1)) << what << ": outside the zone";
        continue;
      }
      const double expected = std::exp(-rate * depth * depth * t);
      EXPECT_NEAR(P.vy()[i], expected, (2 * double(steps) + 3) * test::kUnitRoundoff) << what;
      EXPECT_EQ(P.vx()[i], 0);
      EXPECT_EQ(P.vz()[i], 0);
    }
  }
}

TEST(Damping, AZoneWithoutLengthOrWithABadRateIsRefused) {
  auto make = [](const GivenParams& p) { StyleRegistry::builtin().make_fix("zone", "damping", p); };
  const GivenParams same = {{"from", Vec3{0.3, 0, 0}}, {"to", Vec3{0.3, 0, 0}}};
  const GivenParams negative = {{"from", Vec3{0, 0, 0}}, {"to", Vec3{1, 0, 0}}, {"rate", -1.0}};
  const GivenParams no_start = {{"to", Vec3{1, 0, 0}}};
  EXPECT_ERROR_NAMING(make(same), "parameters 'from' and 'to'", "the same point (0.3, 0, 0)");
  EXPECT_ERROR_NAMING(make(negative), "parameter 'rate'", "-1");
  EXPECT_ERROR_NAMING(make(no_start), "parameter 'from'", "required");
}
