// A submerged inlet: an emitter with an inlet zone (`buffer`) in a tank's wall, under 5 cm of
// water above its top edge (engine/fixes/inlet_zone.hpp). Without the zone the fluid in front of
// the opening would keep it waiting for good; with it:
//  - the inflow is the set rate rho0 A U: the zone moves at U whatever the water ahead does,
//    and a particle enters L = N V / A behind its site's hindmost one. The slope of the emitted
//    mass against time, fitted over 0.6 s (about 60 steps of a site's particle at U = 1 m/s
//    and L ~ s = 1 cm), is within 2% of it (the staircase's steps are 1/60 of the rise and
//    the fit halves what they leave);
//  - the zone feeds the water ahead without squeezing it: beyond the zone and a kernel radius,
//    the largest compression rho/rho0 - 1 stays below 3% (the free surface, where the sums
//    fall short, is no compression) (the still-water bound of the accuracy tests;
//    a Mach number U / c0 = 0.05 for WCSPH). The zone's own particles are not held to it:
//    they follow one another at L = 0.967 s along n, s apart across, so their SPH density is
//    s / L = 3.4% above rho0 (the lattice's mass rule), and the hindmost ones, entering at the
//    wall, see its density too;
//  - the jet goes on: the water within two spacings ahead of the zone, over the opening,
//    moves along n at U within 20% on average (it left the zone at U; the water it enters
//    slows it, the pressure behind it keeps it going).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "engine/core/simulation.hpp"
#include "engine/registry/style_registry.hpp"
#include "engine/sph/lattice.hpp"
#include "test_util.hpp"

using namespace pbf;
using namespace pbf::test;

class SubmergedInlet : public ::testing::TestWithParam<const char*> {};

TEST_P(SubmergedInlet, FeedsTheWaterAheadAtTheSetRate) {
  const std::string solver = GetParam();
  const double s = 0.01, U = 1.0, W = 0.05, depth = 0.12, length = 0.4;
  const double a = W, b = 0.04;  // the opening: the tank's width, 4 cm high, its centre 5 cm up
  Simulation sim;
  sim.set_domain(Domain{{0, 0, 0}, {length, W, 0.4}});
  sim.set_kernel_radius(2 * s);
  const double lo[3] = {0, 0, 0}, hi[3] = {length, W, depth}, rest[3] = {0, 0, 0};
  add_lattice(sim, lo, hi, s, rest);
  const auto& styles = StyleRegistry::builtin();
  sim.add_fix(styles.make_fix("gravity", "gravity", {}));
  if (solver == "pbf") {
    sim.set_timestep(0.001);
    sim.add_fix(styles.make_fix("pbf", "pbf", {}));
  } else {
    sim.set_timestep(0.0002);  // 0.2 h / c0
    sim.add_fix(styles.make_fix("integrator", "leapfrog", {}));
    sim.add_fix(styles.make_fix("wcsph", "wcsph", {{"sound_speed", 20.0}}));
    sim.add_fix(styles.make_fix("viscosity", "sph_viscosity", {}));
  }
  sim.add_fix(styles.make_fix("walls", "box", {}));
  sim.add_fix(styles.make_fix("inlet", "emitter",
                              {{"center", Vec3{0, W / 2, 0.05}}, {"normal", Vec3{1, 0, 0}}, {"axis", Vec3{0, 1, 0}},
                               {"size", Vec2{a, b}}, {"speed", U}, {"buffer", 4 * s}}));
  sim.add_compute(styles.make_compute("in", "flow", {{"fix", std::string("inlet")}}));
  std::vector<double> v, times, masses;
  double worst = 0, ahead_sum = 0;
  long ahead_count = 0;
  sim.run_until(0.1);  // the start: the zone sets off, a wave leaves it
  while (sim.time() < 0.7 - 1e-9) {
    sim.run(10);
    sim.find_compute("in")->evaluate(sim, v);
    times.push_back(sim.time());
    masses.push_back(v[1]);  // (count, mass)
    const real* rho = sim.solver_density();
    const Particles& P = sim.particles();
    for (std::size_t i = 0; i < P.size(); ++i) {
      if (P.x()[i] > 0.04 + 2 * s) worst = std::max(worst, rho[i] / 1000.0 - 1);
      const bool over = std::fabs(P.z()[i] - 0.05) < b / 2;
      if (over && P.x()[i] > 0.04 && P.x()[i] < 0.04 + 2 * s) ahead_sum += P.vx()[i], ++ahead_count;
    }
  }
  auto slope = [&](const std::vector<double>& y) {  // least squares against time
    const double n = double(times.size());
    double st = 0, sy = 0, stt = 0, sty = 0;
    for (std::size_t k = 0; k < times.size(); ++k)
      st += times[k], sy += y[k], stt += times[k] * times[k], sty += times[k] * y[k];
    return (n * sty - st * sy) / (n * stt - st * st);
  };
  const double set_rate = 1000 * a * b * U, rate = slope(masses);
  const double ahead = ahead_sum / double(std::max(1L, ahead_count));
  std::printf("%s: %.4g kg/s (set %.4g), compression ahead at most %.3g, velocity just ahead %.3g m/s\n",
              solver.c_str(), rate, set_rate, worst, ahead);
  EXPECT_NEAR(rate, set_rate, 0.02 * set_rate);
  EXPECT_LT(worst, 0.03);
  EXPECT_NEAR(ahead, U, 0.2 * U);
}

INSTANTIATE_TEST_SUITE_P(BothSolvers, SubmergedInlet, ::testing::Values("pbf", "wcsph"));
