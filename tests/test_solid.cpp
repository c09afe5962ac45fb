// Solids of any shape: the wall density a solid adds is the analytic box's on flat walls and
// the kernel's integral over the wall at corners; a fast jet does not get through a wall one
// spacing thick (both solvers); fluid created inside a solid is left out; a column at rest
// presses on its container with its weight (both solvers); bad solids are refused with their
// name.
#include <gtest/gtest.h>

#include "engine/sph/kernels.hpp"

#include <array>
#include <cmath>
#include <string>

#include "engine/core/error.hpp"
#include "engine/core/simulation.hpp"
#include "engine/registry/style_registry.hpp"
#include "engine/sph/lattice.hpp"
#include "test_util.hpp"

using namespace pbf;

namespace {

std::unique_ptr<Fix> fix(const std::string& id, const std::string& style, const GivenParams& p = {}) {
  return StyleRegistry::builtin().make_fix(id, style, p);
}

// A block of fluid at 10 mm spacing (h = 2 spacings) in the domain [0, 0.4] x [0, 0.2]^2.
void block(Simulation& sim, const double lo[3], const double hi[3], double vx = 0) {
  sim.set_domain(Domain{{0, 0, 0}, {0.4, 0.2, 0.2}});
  sim.set_kernel_radius(0.02);
  sim.set_timestep(1e-3);
  const double v[3] = {vx, 0, 0};
  add_lattice(sim, lo, hi, 0.01, v);
}

// Wall density at a point, as the solver sees it: sum over the pipeline's boundaries.
double wall_density(Simulation& sim, double x, double y, double z, double grad[3]) {
  for (DensityBoundary* b : sim.density_boundaries()) b->prepare(sim);
  real rho = 0, g[3] = {0, 0, 0};
  for (const DensityBoundary* b : sim.density_boundaries()) b->add_density(sim, real(x), real(y), real(z), DensityBoundary::kNoParticle, rho, g);
  for (int a = 0; a < 3; ++a) grad[a] = g[a];
  return rho;
}

// The fraction of a kernel neighbourhood of (x, y, z) lying in the region `wall` (midpoint
// rule on a fine grid): the exact wall density over rho0 that the map approximates.
template <class Region>
double kernel_share(double x, double y, double z, double h, Region wall) {
  const int n = 120;
  const double c = 2 * h / n;
  const pbf::Kernels K(h);
  double sum = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        const double dx = -h + (i + 0.5) * c, dy = -h + (j + 0.5) * c, dz = -h + (k + 0.5) * c;
        const double r2 = dx * dx + dy * dy + dz * dz;
        if (r2 < h * h && wall(x + dx, y + dy, z + dz)) sum += K.W(real(r2));
      }
  return sum * c * c * c;
}

}  // namespace

// A container that is the domain box gives, on its flat walls, the analytic box's density
// and gradient, within the map's discretisation error: 0.2% of rho0, a fifth of the density
// error the solver leaves.
TEST(Solid, FlatWallsGiveTheAnalyticBoxDensity) {
  const double lo[3] = {0, 0, 0}, hi[3] = {0.1, 0.2, 0.1};
  Simulation with_box, with_solid;
  block(with_box, lo, hi);
  block(with_solid, lo, hi);
  with_box.add_fix(fix("walls", "box"));
  with_solid.add_fix(fix("tank", "solid", {{"shape", std::string("box")}, {"fluid", std::string("inside")},
                                           {"lo", Vec3{0, 0, 0}}, {"hi", Vec3{0.4, 0.2, 0.2}}}));
  for (double z : {0.0, 0.003, 0.005, 0.011, 0.019, 0.03}) {
    double gb[3], gs[3];
    const double rb = wall_density(with_box, 0.2, 0.1, z, gb), rs = wall_density(with_solid, 0.2, 0.1, z, gs);
    EXPECT_NEAR(rs, rb, 3e-3 * 1000) << "z = " << z;
    // The gradient: 2% of it, and a tenth of its scale rho0 / h, for where it fades (near h and
    // beyond, z = 0.019 and 0.03, a relative bound allows nothing); along the wall it vanishes by symmetry.
    EXPECT_NEAR(gs[2], gb[2], 0.02 * std::abs(gb[2]) + 0.1 * 1000 / 0.02) << "z = " << z;
    EXPECT_NEAR(gs[0], 0, 1e-2);
  }
}

// In the corner of a container, three walls overlap in the kernel: the map's fraction is
// the kernel's integral over the walls (shifted by the wall's delta, which the flat-wall
// value at one point gives). Between nodes, interpolation misses the kink the distance has
// on an edge's bisector by up to a third of a cell, up to 0.02 in the fraction.
TEST(Solid, CornerDensityIsTheKernelIntegralOverTheWalls) {
  const double lo[3] = {0, 0, 0}, hi[3] = {0.1, 0.1, 0.1};
  Simulation sim;
  block(sim, lo, hi);
  sim.add_fix(fix("tank", "solid", {{"shape", std::string("box")}, {"fluid", std::string("inside")},
                                    {"lo", Vec3{0, 0, 0}}, {"hi", Vec3{0.4, 0.2, 0.2}}}));
  const double h = 0.02, rho0 = 1000;
  double g[3];
  // delta from a flat wall: find the shift at which the integral matches the map there.
  const double flat = wall_density(sim, 0.2, 0.1, 0.006, g) / rho0;
  double dlo = -0.01, dhi = 0.01;
  for (int it = 0; it < 30; ++it) {
    const double mid = 0.5 * (dlo + dhi);
    (kernel_share(0.2, 0.1, 0.006, h, [&](double, double, double z) { return z < -mid; }) > flat ? dlo : dhi) = mid;
  }
  const double delta = 0.5 * (dlo + dhi);
  for (double s : {0.003, 0.006, 0.012}) {
    const double exact = kernel_share(s, s, s, h, [&](double x, double y, double z) {
      return x < -delta || y < -delta || z < -delta;
    });
    EXPECT_NEAR(wall_density(sim, s, s, s, g) / rho0, exact, 0.04) << "at " << s << " m from three walls";
  }
}

// A jet at 10 m/s against a wall one spacing (10 mm) thick, v dt = 0.4 h: no particle gets
// into the wall or beyond it.
class Jet : public ::testing::TestWithParam<std::string> {};

TEST_P(Jet, DoesNotGoThroughAWallOneSpacingThick) {
  Simulation sim;
  const double lo[3] = {0.02, 0.06, 0.06}, hi[3] = {0.22, 0.14, 0.14};
  block(sim, lo, hi, 10.0);
  sim.set_timestep(0.4 * 0.02 / 10);
  sim.add_fix(fix("walls", "box"));
  sim.add_fix(fix("plate", "solid", {{"shape", std::string("box")}, {"lo", Vec3{0.3, -0.1, -0.1}},
                                     {"hi", Vec3{0.31, 0.3, 0.3}}}));
  if (GetParam() == "pbf") {
    sim.add_fix(fix("pbf", "pbf"));
  } else {
    sim.add_fix(fix("integrator", "leapfrog"));
    sim.add_fix(fix("wcsph", "wcsph", {{"sound_speed", 100.0}}));
    sim.add_fix(fix("viscosity", "sph_viscosity"));
    sim.add_fix(fix("cfl", "cfl"));
  }
  const std::size_t n = sim.particles().size();
  double front = 0;
  while (sim.time() < 0.06) {  // the jet's head arrives at 8 ms; its tail at 28 ms
    sim.run(GetParam() == "pbf" ? 5 : 50);
    const auto& P = sim.particles();
    for (std::size_t i = 0; i < P.size(); ++i) {
      front = std::max(front, double(P.x()[i]));
      ASSERT_LT(P.x()[i], 0.3) << "particle " << P.ids()[i] << " at t = " << sim.time();
    }
  }
  EXPECT_EQ(sim.particles().size(), n);
  EXPECT_GT(front, 0.29);  // the jet did reach the wall
}

INSTANTIATE_TEST_SUITE_P(BothSolvers, Jet, ::testing::Values("pbf", "wcsph"));

TEST(Solid, FluidCreatedInsideIsLeftOut) {
  Simulation sim;
  const double lo[3] = {0, 0, 0}, hi[3] = {0.1, 0.1, 0.1};
  block(sim, lo, hi);
  ASSERT_EQ(sim.particles().size(), 1000u);
  // A ball of radius 0.03 m at the block's centre holds about 4/3 pi 3^3 = 113 sites.
  sim.add_fix(fix("ball", "solid", {{"shape", std::string("sphere")}, {"center", Vec3{0.05, 0.05, 0.05}},
                                    {"radius", 0.03}}));
  sim.add_fix(fix("pbf", "pbf"));
  sim.run(1);
  const auto& P = sim.particles();
  // Left out: the sites inside it or nearer than the contact distance, half a spacing (0.005 m),
  // less a tenth of a spacing, which the first projection would push out with a kick of
  // (gap - d) / dt. The lattice sites lie at (i + 1/2) 0.01 from the corner: 4 r^2 / 0.01^2
  // is a sum of three odd squares, 3 mod 8, so none lies between 0.034 and 0.035 m (46.2 to 49).
  // The others keep their ids, the lattice's site numbers: the ids left are the sites outside.
  std::size_t inside = 0;
  std::vector<std::int64_t> sites_outside;
  for (int i = 0; i < 1000; ++i)
    if (std::hypot(0.005 + 0.01 * (i % 10) - 0.05, 0.005 + 0.01 * (i / 10 % 10) - 0.05,
                   0.005 + 0.01 * (i / 100) - 0.05) >= 0.035)
      sites_outside.push_back(i);
  EXPECT_EQ(P.size(), sites_outside.size());
  std::vector<std::int64_t> ids(P.ids(), P.ids() + P.size());
  std::sort(ids.begin(), ids.end());
  EXPECT_EQ(ids, sites_outside);
  for (std::size_t i = 0; i < P.size(); ++i)
    inside += std::hypot(P.x()[i] - 0.05, P.y()[i] - 0.05, P.z()[i] - 0.05) < 0.03 - 1e-9;
  EXPECT_EQ(inside, 0u);
}

// Water at rest on its lattice around a ball, released: in the first step only gravity acts on
// it, so no particle moves faster than g dt (twice that allowed). A lattice site left between
// the surface and the contact distance was put back there by the first projection, a move the
// step turned into speed: 2.2 m/s here, before such sites were left out or moved at the start.
TEST(Solid, FluidAroundASolidStartsWithoutAKick) {
  Simulation sim;
  const double lo[3] = {0, 0, 0}, hi[3] = {0.1, 0.1, 0.1};
  block(sim, lo, hi);
  sim.add_fix(fix("gravity", "gravity"));
  sim.add_fix(fix("pbf", "pbf"));
  sim.add_fix(fix("walls", "box"));
  sim.add_fix(fix("ball", "solid", {{"shape", std::string("sphere")}, {"center", Vec3{0.05, 0.05, 0.05}},
                                    {"radius", 0.03}}));
  sim.run(1);
  const auto& P = sim.particles();
  double fastest = 0;
  for (std::size_t i = 0; i < P.size(); ++i) fastest = std::max(fastest, double(std::hypot(P.vx()[i], P.vy()[i], P.vz()[i])));
  EXPECT_LT(fastest, 2 * 9.81 * sim.timestep());
}

TEST(Solid, RefusesBadSolidsByName) {
  auto refused = [](const GivenParams& p, const std::string& text) {
    try {
      Simulation sim;
      const double lo[3] = {0, 0, 0}, hi[3] = {0.1, 0.1, 0.1};
      block(sim, lo, hi);
      sim.add_fix(fix("thing", "solid", p));
      sim.add_fix(fix("pbf", "pbf"));
      sim.run(1);
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
      return;
    }
    ADD_FAILURE() << "accepted; expected: " << text;
  };
  refused({{"shape", std::string("sphere")}, {"radius", 0.1}}, "'center'");
  refused({{"shape", std::string("box")}, {"lo", Vec3{0, 0, 0}}, {"hi", Vec3{0, 1, 1}}}, "'hi' must exceed 'lo'");
  refused({}, "'file'");
  refused({{"file", std::string("/nonexistent/tank.obj")}}, "/nonexistent/tank.obj");
  refused({{"shape", std::string("sphere")}, {"center", Vec3{5, 5, 5}}, {"radius", 0.1}}, "outside the domain");
  refused({{"shape", std::string("box")}, {"lo", Vec3{0.2, 0, 0}}, {"hi", Vec3{0.204, 0.2, 0.2}}},
          "less than the particle spacing");
  refused({{"shape", std::string("box")}, {"fluid", std::string("inside")}, {"lo", Vec3{0.2, 0, 0}},
           {"hi", Vec3{0.3, 0.05, 0.05}}},
          "leaves no particle");
}

TEST(Solid, RefusesParametersOfAnotherShape) {
  try {
    fix("thing", "solid", {{"shape", std::string("box")}, {"lo", Vec3{0, 0, 0}}, {"hi", Vec3{1, 1, 1}}, {"radius", 0.1}});
    ADD_FAILURE() << "accepted a radius for a box";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'radius' does not apply to shape 'box'"), std::string::npos) << e.what();
  }
}

// A column at rest in a solid container pushes on it with its weight: the load's z component,
// averaged over 1 s after a settling second, is -M g within 2%, and the sideways forces
// cancel (within 2% of the weight), for both solvers.
class ColumnLoad : public ::testing::TestWithParam<std::string> {};

TEST_P(ColumnLoad, IsTheColumnsWeight) {
  Simulation sim;
  sim.set_domain(Domain{{0, 0, 0}, {0.1, 0.1, 0.3}});
  sim.set_kernel_radius(0.02);
  sim.set_timestep(0.004);
  const double lo[3] = {0, 0, 0}, hi[3] = {0.1, 0.1, 0.15}, v[3] = {0, 0, 0};
  add_lattice(sim, lo, hi, 0.01, v);
  sim.add_fix(fix("gravity", "gravity"));
  sim.add_fix(fix("tank", "solid", {{"shape", std::string("box")}, {"fluid", std::string("inside")},
                                    {"lo", Vec3{0, 0, 0}}, {"hi", Vec3{0.1, 0.1, 0.3}}}));
  if (GetParam() == "pbf") {
    sim.add_fix(fix("pbf", "pbf"));
  } else {
    sim.add_fix(fix("integrator", "leapfrog"));
    sim.add_fix(fix("wcsph", "wcsph"));
    sim.add_fix(fix("viscosity", "sph_viscosity"));
    sim.add_fix(fix("cfl", "cfl"));
  }
  sim.add_compute(StyleRegistry::builtin().make_compute("f", "load", {{"solid", std::string("tank")}}));
  double weight = 0;
  for (std::size_t i = 0; i < sim.particles().size(); ++i) weight += sim.particles().mass()[i] * 9.81;
  sim.run_until(1.0);
  double impulse[3] = {0, 0, 0}, time = 0;
  std::vector<double> f;
  while (sim.time() < 2.0 - 1e-9) {
    sim.run(1);
    sim.find_compute("f")->evaluate(sim, f);
    for (int a = 0; a < 3; ++a) impulse[a] += f[a] * sim.timestep();
    time += sim.timestep();
  }
  // Newton: over the second the column's momentum changes by M dv, dv below its jostling
  // (0.01 m/s against g t = 9.8 m/s: 0.1%); 2% is for the settling and the contact's share.
  EXPECT_NEAR(impulse[2] / time / -weight, 1.0, 0.02);
  EXPECT_NEAR(impulse[0] / time / weight, 0.0, 0.02);
  EXPECT_NEAR(impulse[1] / time / weight, 0.0, 0.02);
}

INSTANTIATE_TEST_SUITE_P(BothSolvers, ColumnLoad, ::testing::Values("pbf", "wcsph"));

TEST(Solid, ALoadOfAnUnknownSolidIsRefusedByName) {
  Simulation sim;
  const double lo[3] = {0, 0, 0}, hi[3] = {0.1, 0.1, 0.1};
  block(sim, lo, hi);
  sim.add_fix(fix("tank", "solid", {{"shape", std::string("box")}, {"fluid", std::string("inside")},
                                    {"lo", Vec3{0, 0, 0}}, {"hi", Vec3{0.4, 0.2, 0.2}}}));
  sim.add_compute(StyleRegistry::builtin().make_compute("f", "load", {{"solid", std::string("tnak")}}));
  std::vector<double> values;
  EXPECT_ERROR_NAMING(sim.find_compute("f")->evaluate(sim, values), "'tnak'", "did you mean 'tank'");
}

// A no_slip solid takes a touching particle's whole tangential velocity (relative to the
// wall; this one is at rest): a layer of fluid sliding at 0.5 m/s over a solid floor stops
// dead where it touches it, after one step, in both solvers and both precisions; with
// no_slip off and no friction it slides on at the speed it had, on average over the layer (the
// solver's sideways corrections, up to 1% at the block's sides, cancel in the mean as the
// block is symmetric about its centre: 1e-3 allows their rounding and the block's slight
// asymmetry, its front, after moving 0.5 mm in a step). The contact: the
// lattice's first layer starts half a spacing above the floor, where the solid keeps it.
// Bound for "stops": the normal's rounding, u, times the speed (the wall's velocity is 0).
TEST(Solid, ANoSlipFloorStopsTheFluidSlidingOnIt) {
  for (const std::string solver : {"pbf", "wcsph"})
    for (const bool no_slip : {true, false}) {
      Simulation sim;
      const double U = 0.5, floor = 0.02;
      block(sim, std::array<double, 3>{0.15, 0.05, floor}.data(), std::array<double, 3>{0.25, 0.15, 0.06}.data(), U);
      sim.set_timestep(solver == "pbf" ? 1e-3 : 1e-4);
      sim.add_fix(fix("gravity", "gravity"));
      sim.add_fix(fix("floor", "solid", {{"shape", std::string("box")}, {"lo", Vec3{0, 0, 0}},
                                         {"hi", Vec3{0.4, 0.2, floor}}, {"no_slip", no_slip}, {"friction", 0.0}}));
      if (solver == "pbf") {
        sim.add_fix(fix("pbf", "pbf"));
      } else {
        sim.add_fix(fix("integrator", "leapfrog"));
        sim.add_fix(fix("wcsph", "wcsph", {{"sound_speed", 20.0}}));
      }
      sim.run(1);
      const auto& P = sim.particles();
      int touching = 0;
      double slide = 0;
      for (std::size_t i = 0; i < P.size(); ++i) {
        if (P.z()[i] > floor + 0.0051) continue;  // half a spacing and the solid's hairs (1e-3 of a map cell)
        ++touching;
        const std::string what = solver + (no_slip ? ", no slip" : ", free slip") + ": particle " +
                                 std::to_string(P.ids()[i]);
        if (no_slip) {
          EXPECT_NEAR(P.vx()[i], 0.0, 4 * test::kUnitRoundoff * U) << what;
          EXPECT_NEAR(P.vy()[i], 0.0, 4 * test::kUnitRoundoff * U) << what;
        } else {
          slide += P.vx()[i];
        }
      }
      EXPECT_EQ(touching, 100) << solver << ": the whole first layer (10 x 10) touches the floor";
      if (!no_slip) EXPECT_NEAR(slide / touching, U, 1e-3 * U) << solver << ": the layer's mean speed";
    }
}
