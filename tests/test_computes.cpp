// Computes read what they say they read, from every particle, in id order: `speed` counts all
// three velocity components, `extent` sees every particle (the first in memory too), and the
// per-particle `density` gives each id its own particle's SPH sum. Each compares with a value
// the test computes itself from the particles.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/core/simulation.hpp"
#include "engine/registry/style_registry.hpp"
#include "engine/sph/lattice.hpp"
#include "test_util.hpp"

using namespace pbf;

namespace {

std::vector<double> evaluate(Simulation& sim, const std::string& style) {
  auto c = StyleRegistry::builtin().make_compute("c", style, {});
  std::vector<double> v;
  std::vector<std::int64_t> ids;
  if (c->per_particle()) c->evaluate_per_particle(sim, ids, v);
  else c->evaluate(sim, v);
  return v;
}

// A 5^3 block at spacing 0.01 (h = 0.02) in the open, no walls.
void block(Simulation& sim) {
  sim.set_domain(Domain{{0, 0, 0}, {0.2, 0.2, 0.2}});
  sim.set_kernel_radius(0.02);
  sim.set_timestep(0.001);
  const double lo[3] = {0.05, 0.05, 0.05}, hi[3] = {0.1, 0.1, 0.1}, v[3] = {0, 0, 0};
  add_lattice(sim, lo, hi, 0.01, v);
}

}  // namespace

// Velocities (i mod 3 - 1) * 0.1 along x and y, and a vertical one that grows with i, largest
// at the last particle: the largest speed is that particle's, all three components counted,
// and the mean is the mean of the norms (both in double from the stored reals; the sum's
// rounding is the only difference: n u of the sum).
TEST(Computes, SpeedCountsEveryComponent) {
  Simulation sim;
  block(sim);
  auto& P = sim.particles();
  const std::size_t n = P.size();
  double most = 0, sum = 0;
  for (std::size_t i = 0; i < n; ++i) {
    P.vx()[i] = real(0.1 * (double(i % 3) - 1));
    P.vy()[i] = real(0.1 * (double((i + 1) % 3) - 1));
    P.vz()[i] = real(-0.5 * double(i) / double(n));
    const double vx = P.vx()[i], vy = P.vy()[i], vz = P.vz()[i], speed = std::sqrt(vx * vx + vy * vy + vz * vz);
    most = std::max(most, speed);
    sum += speed;
  }
  const auto v = evaluate(sim, "speed");
  EXPECT_DOUBLE_EQ(v.at(0), most);
  EXPECT_NEAR(v.at(1), sum / double(n), double(n) * 1e-16 * sum / double(n));
}

// Each particle in turn, the first and the last in memory among them, moved past every other
// along each axis, both ways: the extent is its coordinate.
TEST(Computes, ExtentSeesEveryParticle) {
  Simulation sim;
  block(sim);
  auto& P = sim.particles();
  real* c[3] = {P.x(), P.y(), P.z()};
  for (std::size_t i : {std::size_t{0}, P.size() / 2, P.size() - 1})
    for (int a = 0; a < 3; ++a)
      for (int side = 0; side < 2; ++side) {
        const real kept = c[a][i];
        c[a][i] = real(side == 0 ? 0.01 : 0.19);  // beyond the block's 0.055 .. 0.095
        const auto v = evaluate(sim, "extent");
        EXPECT_EQ(v.at(2 * a + side), double(c[a][i])) << "particle " << i << ", axis " << a << ", side " << side;
        c[a][i] = kept;
      }
}

// With no walls and PBF's summed density, the per-particle density of id k is the SPH sum
// m sum_j W(|x_k - x_j|) at the particle that has id k, summed here in double over all pairs:
// the same terms, so the same value but for the sum's rounding (the engine sums at most n terms
// in real, each W rounded too: 2 (n + 16) u of it, generously). The
// block's corners see fewer neighbours than its centre, so a value given to another id is
// far off.
TEST(Computes, PerParticleDensityIsEachIdsOwnSum) {
  Simulation sim;
  block(sim);
  sim.add_fix(StyleRegistry::builtin().make_fix("pbf", "pbf", {}));
  sim.run(25);  // past the first reordering along the grid: memory order is no longer id order
  const auto& P = sim.particles();
  const Kernels& K = sim.kernels();
  const auto by_id = evaluate(sim, "density");
  ASSERT_EQ(by_id.size(), P.size());
  double least = INFINITY, most = 0;
  for (std::size_t i = 0; i < P.size(); ++i) {
    double rho = 0;
    for (std::size_t j = 0; j < P.size(); ++j) {
      const double dx = double(P.x()[i]) - P.x()[j], dy = double(P.y()[i]) - P.y()[j],
                   dz = double(P.z()[i]) - P.z()[j];
      rho += double(P.mass()[j]) * double(K.W(real(dx * dx + dy * dy + dz * dz)));
    }
    least = std::min(least, rho);
    most = std::max(most, rho);
    const double bound = 2 * double(P.size() + 16) * test::kUnitRoundoff * rho;
    EXPECT_NEAR(by_id.at(static_cast<std::size_t>(P.ids()[i])), rho, bound)
        << "id " << P.ids()[i];
  }
  EXPECT_GT(most - least, 0.3 * most);  // corners against the centre: the test can tell them apart
  std::size_t out_of_order = 0;
  for (std::size_t i = 0; i < P.size(); ++i) out_of_order += P.ids()[i] != static_cast<std::int64_t>(i);
  EXPECT_GT(out_of_order, 0u);
}

// A gauge reads the level where the fluid fraction f(z) = sum_j (m_j / rho0) W crosses 1/2
// (engine/computes/gauge.cpp): it samples f every quarter spacing down its line and
// interpolates linearly between the two samples around the crossing. Against the crossing of
// the same f summed here over every particle in double precision and found by bisection, the
// level may then be off by the linear interpolation's error only: M dz^2 / (8 |f'|), M the
// largest |f''| between the samples, dz their distance (measured here on the reference f), and
// rounding (f's, 1e-6 over |f'| ~ 50 per metre). The lines' feet are spread over one sample
// interval, so the crossing falls at different places between samples: a level interpolated from
// the wrong end of the interval (off by dz |1 - 2t|, t the crossing's place in it) misses on some.
TEST(Computes, AGaugeFindsWhereTheFluidFractionCrossesOneHalf) {
  Simulation sim;
  sim.set_domain(Domain{{0, 0, 0}, {0.2, 0.2, 0.2}});
  sim.set_kernel_radius(0.02);
  sim.set_timestep(0.001);
  const double lo[3] = {0.05, 0.05, 0}, hi[3] = {0.15, 0.15, 0.06}, v[3] = {0, 0, 0};
  add_lattice(sim, lo, hi, 0.01, v);
  const double x = 0.1, y = 0.1, dz = 0.01 / 4, top = 0.2;
  const Points feet = {{x, y, 0}, {x, y, 0.3 * dz}, {x, y, 0.55 * dz}, {x, y, 0.8 * dz}};
  auto gauge = StyleRegistry::builtin().make_compute("g", "gauge", {{"points", feet}});
  std::vector<double> levels;
  gauge->evaluate(sim, levels);
  ASSERT_EQ(levels.size(), feet.size());

  const auto& P = sim.particles();
  const Kernels& K = sim.kernels();
  const double rho0 = sim.rest_density();
  auto f = [&](double z) {
    double sum = 0;
    for (std::size_t j = 0; j < P.size(); ++j) {
      const double dx = x - P.x()[j], dy = y - P.y()[j], dzj = z - P.z()[j], r2 = dx * dx + dy * dy + dzj * dzj;
      if (r2 < double(K.h2)) sum += double(P.mass()[j]) / rho0 * double(K.W(real(r2)));
    }
    return sum;
  };
  // The highest crossing: down from the top in steps of dz / 100, then bisection.
  double above = top, below = top;
  while (f(below) < 0.5) above = below, below -= dz / 100;
  for (int k = 0; k < 60; ++k) {
    const double mid = (above + below) / 2;
    (f(mid) >= 0.5 ? below : above) = mid;
  }
  const double crossing = below, e = dz / 10;
  double curvature = 0;  // the largest |f''| within a sample interval of the crossing
  for (double z = crossing - dz; z <= crossing + dz; z += e)
    curvature = std::max(curvature, std::fabs(f(z + e) - 2 * f(z) + f(z - e)) / (e * e));
  const double slope = std::fabs(f(crossing + e) - f(crossing - e)) / (2 * e);
  ASSERT_GT(slope, 10.0);  // a surface, not a plateau
  const double bound = curvature * dz * dz / (8 * slope) + 1e-6 / slope;
  EXPECT_LT(bound, 0.1 * dz);  // the check can tell a sample interval's parts apart
  for (std::size_t k = 0; k < feet.size(); ++k)
    EXPECT_NEAR(levels[k] + feet[k][2], crossing, bound) << "the line from z0 = " << feet[k][2];
}
