// The leapfrog (kick-drift-kick) on free fall, where its answer is exact: under a constant
// acceleration every step after the first is exact, and the first (a drift with v_0, then a
// whole kick) leaves the documented offset. A restart in the middle carries the fix's state
// "has taken its first step".
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "engine/core/simulation.hpp"
#include "engine/io/restart.hpp"
#include "engine/registry/style_registry.hpp"
#include "test_util.hpp"

using namespace pbf;

namespace {

constexpr double kG = 9.81, kDt = 0.02;
// Three particles a spacing apart, thrown together (they stay a spacing apart, h = 2
// spacings, as a restart's check of h against the spacing wants), ids 0 to 2; no fix
// couples them: nothing but gravity acts.
constexpr double kStart[3][3] = {{0, 0, 2}, {0.01, 0, 2}, {0, 0.01, 2.01}};
constexpr double kThrow[3] = {1, -0.5, 2};

void falling_particles(Simulation& sim) {
  sim.set_domain(Domain{{-10, -10, -10}, {10, 10, 10}});
  sim.set_kernel_radius(0.02);
  sim.set_timestep(kDt);
  for (int p = 0; p < 3; ++p) {
    const real x[3] = {real(kStart[p][0]), real(kStart[p][1]), real(kStart[p][2])};
    const real v[3] = {real(kThrow[0]), real(kThrow[1]), real(kThrow[2])};
    sim.particles().add(x, v, 1e-3);
  }
}

void add_pipeline(Simulation& sim) {
  const auto& styles = StyleRegistry::builtin();
  sim.add_fix(styles.make_fix("integrator", "leapfrog", {}));
  sim.add_fix(styles.make_fix("gravity", "gravity", {{"acceleration", Vec3{0, 0, -kG}}}));
}

// After `steps` steps from the start (t = steps dt), with v_n = v_0 + n dt g:
//   first step:  x_1 = x_0 + dt v_0 (no a_0 to half-kick with),  v_1 = v_0 + dt g
//   later steps: x_{n+1} = x_n + dt v_n + dt^2 g / 2,  v_{n+1} = v_n + dt g   (exact for constant g)
// so v = v_0 + g t exactly and x = x_0 + v_0 t + g t^2 / 2 - g dt^2 / 2: the first step's
// missing half-kick is the only departure from the exact path.
// Rounding: each step's two kicks round v to u vmax and add real(dt/2) real(g), itself 2u
// off, so |dv| <= steps (2 u vmax + 2u g dt) <= 4 steps u vmax; each drift rounds x to
// u xmax and carries dv: |dx| <= steps u xmax + t |dv|.
// A first kick of dt/2 leaves v off by g dt / 2 = 0.098 m/s; a restart that forgot the first
// step was taken drifts its next step without the half-kick, x off by g dt^2 / 2 = 2 mm.
void expect_free_fall(const Simulation& sim, int steps) {
  const double t = steps * kDt, u = test::kUnitRoundoff;
  const auto& P = sim.particles();
  const auto index = P.index_of_id();
  for (int p = 0; p < 3; ++p) {
    const std::size_t i = index[static_cast<std::size_t>(p)];
    const double g[3] = {0, 0, -kG};
    const double x[3] = {P.x()[i], P.y()[i], P.z()[i]}, v[3] = {P.vx()[i], P.vy()[i], P.vz()[i]};
    double vmax = 0, xmax = 0;
    for (int c = 0; c < 3; ++c) {
      vmax = std::max(vmax, std::fabs(kThrow[c]) + kG * t);
      xmax = std::max(xmax, std::fabs(kStart[p][c]) + std::fabs(kThrow[c]) * t + kG * t * t / 2);
    }
    const double v_tolerance = 4 * steps * u * vmax, x_tolerance = steps * u * xmax + t * v_tolerance;
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(v[c], kThrow[c] + g[c] * t, v_tolerance) << "particle " << p << ", axis " << c;
      EXPECT_NEAR(x[c], kStart[p][c] + kThrow[c] * t + g[c] * (t * t - kDt * kDt) / 2, x_tolerance)
          << "particle " << p << ", axis " << c;
    }
  }
}

}  // namespace

TEST(Leapfrog, FreeFallIsExactAcrossARestart) {
  const auto dir = test::temp_dir("leapfrog");
  const auto restart = (dir / "half.restart").string();
  Simulation first;
  falling_particles(first);
  add_pipeline(first);
  first.run(20);
  expect_free_fall(first, 20);
  write_restart(first, restart);

  Simulation continued;
  read_restart(continued, restart);
  add_pipeline(continued);
  continued.run(30);
  expect_free_fall(continued, 50);  // t = 1 s, 4.9 m fallen
}
