// The box walls: restitution per impact, friction per second (independent of the time
// step), positions kept inside.
#include <gtest/gtest.h>

#include <cmath>

#include <string>

#include "engine/sph/density_boundary.hpp"
#include "engine/sph/lattice.hpp"
#include "engine/core/simulation.hpp"
#include "engine/registry/style_registry.hpp"
#include "test_util.hpp"

using namespace pbf;

namespace {

// One particle (alone, so the one-sided density constraint leaves it be) in a unit box,
// near x = 0: PBF velocities are position differences over dt, resolved to ulp(x) / dt, which
// in single precision is 6e-5 m/s at x = 0.5 with dt = 1 ms, too coarse for this test.
void single_particle(Simulation& sim, double z, double vx, double dt) {
  Domain d;
  sim.set_domain(d);
  sim.set_kernel_radius(0.02);
  sim.set_timestep(dt);
  const double lo[3] = {0.0, 0.5, z}, hi[3] = {0.01, 0.51, z + 0.01}, v[3] = {vx, 0, 0};
  add_lattice(sim, lo, hi, 0.01, v);
  ASSERT_EQ(sim.particles().size(), 1u);
  sim.add_fix(StyleRegistry::builtin().make_fix("pbf", "pbf", {}));
}

}  // namespace

TEST(Box, RestitutionReturnsThatShareOfTheImpactSpeed) {
  for (double e : {0.0, 0.5, 0.9}) {
    Simulation sim;
    single_particle(sim, 0.1, 0, 1e-4);
    sim.add_fix(StyleRegistry::builtin().make_fix("g", "gravity", {}));
    sim.add_fix(StyleRegistry::builtin().make_fix("walls", "box", {{"restitution", e}}));
    auto vz = [&] { return double(sim.particles().vz()[0]); };  // arrays move when reordered
    double impact = 0, rebound = 0;
    for (int s = 0; s < 3000; ++s) {  // falls 0.1 m in 0.14 s, then flies up again
      const double before = vz();
      sim.run(1);
      if (before < 0 && vz() >= 0 && impact == 0) impact = -before;
      if (impact > 0) rebound = std::max(rebound, vz());
    }
    ASSERT_GT(impact, 1.3);  // sqrt(2 g 0.1) = 1.40 m/s
    // 2e-3 = 2 g dt: the speeds are read a step before and after the bounce, each up to g dt from
    // the bounce's; plus 1%. The three restitutions' rebounds lie 0.4 impact or more apart.
    EXPECT_NEAR(rebound, e * impact, 0.01 * impact + 2e-3) << "restitution " << e;
  }
}

TEST(Box, FrictionIsARatePerSecondWhateverTheTimeStep) {
  double speed[2];
  for (int k = 0; k < 2; ++k) {
    const double dt = k == 0 ? 2e-3 : 1e-3;
    Simulation sim;
    single_particle(sim, 0.0, 0.2, dt);
    sim.add_fix(StyleRegistry::builtin().make_fix("g", "gravity", {}));
    sim.add_fix(StyleRegistry::builtin().make_fix("walls", "box", {{"friction", 2.0}}));
    sim.run(static_cast<std::int64_t>(std::lround(1.0 / dt)));
    speed[k] = sim.particles().vx()[0];
  }
  // It starts 5 mm above the floor, at the default contact distance (half a spacing): it
  // touches the wall and slides from t = 0 to 1 s.
  // exp(-rate dt) a step is exp(-2) after 1 s at any dt: 5e-4 (2% of 0.027 m/s) is for a step
  // or two out of contact (rate dt = 0.4% each) and single precision's ulp(x) / dt a step. A
  // rate per step would give exp(-4) at 1 ms, 0.023 m/s off.
  EXPECT_NEAR(speed[0], 0.2 * std::exp(-2.0), 5e-4);
  EXPECT_NEAR(speed[1], speed[0], 5e-4);  // not exp(-2 * 2) with half the step
}

// The density the walls add and its gradient, which the solver uses together (PBF's
// multiplier divides by the gradient's square, its correction moves along it): the gradient
// must be the derivative of the density at every face. At a point h/3 inside each face in
// turn (off the others by more than h, so one face counts), the gradient along the face's
// axis against the central difference over +-e, e = h/1000, and its sign: the wall's density
// grows toward the wall, so it points out of the fluid, -x at the lower x face, +x at the upper.
// Error bound: the difference's truncation, e^2/6 |rho'''|, with |f'''| <= 20/h^3 for the
// wall fraction's polynomial in u = d/h (engine/sph/wall_density.hpp), is 3e-6 rho0/h; its
// rounding, a few units of rho's last place over 2e: 8 u rho0 / (2 e) = 4000 u rho0 / h
// (2.4e-4 rho0/h in single precision), over the step the rounded points make. The gradient
// itself is of order rho0/h (0.6 rho0/h here, 1.5 rho0/h at the face).
TEST(Box, TheWallDensitysGradientIsItsDerivativeAtEveryFace) {
  Simulation sim;
  sim.set_domain(Domain{{0, 0, 0}, {0.2, 0.2, 0.2}});
  sim.set_kernel_radius(0.02);
  sim.set_timestep(1e-3);
  const double lo[3] = {0.08, 0.08, 0.08}, hi[3] = {0.12, 0.12, 0.12}, v[3] = {0, 0, 0};
  add_lattice(sim, lo, hi, 0.01, v);  // particles set the mass, hence the wall's offset delta
  sim.add_fix(StyleRegistry::builtin().make_fix("walls", "box", {}));
  const auto& walls = sim.density_boundaries();
  ASSERT_EQ(walls.size(), 1u);
  walls[0]->prepare(sim);
  const double h = 0.02, rho0 = sim.rest_density(), e = h / 1000;
  auto density = [&](const double p[3], double grad[3]) {
    real rho = 0, g[3] = {0, 0, 0};
    walls[0]->add_density(sim, real(p[0]), real(p[1]), real(p[2]), DensityBoundary::kNoParticle, rho, g);
    for (int a = 0; a < 3; ++a) grad[a] = g[a];
    return double(rho);
  };
  const double tolerance = 3e-6 * rho0 / h + 4000 * test::kUnitRoundoff * rho0 / h;
  for (int a = 0; a < 3; ++a)
    for (int side : {-1, 1}) {
      double p[3] = {0.1, 0.1, 0.1}, grad[3], unused[3];
      p[a] = side < 0 ? h / 3 : 0.2 - h / 3;
      density(p, grad);
      double below[3] = {p[0], p[1], p[2]}, above[3] = {p[0], p[1], p[2]};
      below[a] -= e, above[a] += e;
      // Over the step the stored positions make (the points are rounded to reals).
      const double step = double(real(above[a])) - double(real(below[a]));
      const double difference = (density(above, unused) - density(below, unused)) / step;
      const std::string face = std::string(side < 0 ? "lower " : "upper ") + "xyz"[a] + " face";
      EXPECT_NEAR(grad[a], difference, tolerance) << face;
      EXPECT_GT(grad[a] * side, 0.2 * rho0 / h) << face << ": the gradient points out of the fluid";
      for (int b = 0; b < 3; ++b)
        if (b != a) EXPECT_EQ(grad[b], 0.0) << face << ": a component along the face";
    }
}
