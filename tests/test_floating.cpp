// Bodies the fluid moves (a `solid` with a density or a mass; engine/fixes/solid_dynamics.*):
// their mass properties, the ways they are held, and the coupling with both solvers.
//  - A sphere's and a cylinder's inertia, placed, turned and stretched, are the closed forms'
//    (an ellipsoid's m (b^2 + c^2) / 5; a cylinder's m r^2 / 2 about its axis).
//  - Out of the water a body falls freely: the Verlet kicks of a constant force are exact, so
//    z(t) = z0 - g t^2 / 2 to round-off; a body held to heave keeps its x, y and its turn.
//  - Archimedes: a box of relative density 0.5 (or 0.75) floats with its draft d = (rho_b /
//    rho) H within 3% (the bound) of the water level the gauge measures, and does not
//    drift (its mean over the last second within 1 mm of the second before); both solvers.
//    A half-dense sphere (a quarter model) floats with its centre at the level within 3% of R.
//  - Springs: a bob hangs at its stretch m g / k and swings at 2 pi sqrt(m / k); with a damper
//    its swing decays as exp(-c t / 2m); two bodies tied together keep their momentum.
//  - Solids a motion moves are contacts: a lifted platform carries a crate up, a pushed plate
//    drives one along the floor.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "body_scenes.hpp"
#include "engine/geometry/motion.hpp"
#include "test_util.hpp"

using namespace pbf;
using pbf::test::body_of;
using pbf::test::corner_block;
using pbf::test::corner_scene;
using pbf::test::dynamics_of;
using pbf::test::fix;

TEST(Body, AStretchedTurnedSphereHasTheEllipsoidsInertia) {
  // Semi-axes 0.1 * {1, 2, 3}, turned 90 degrees about z: the long y axis lies along x.
  const double rho = 500, a = 0.1, b = 0.2, c = 0.3;
  const RigidBody body = body_of({{"shape", std::string("sphere")}, {"center", Vec3{0, 0, 0}}, {"radius", 0.1},
                                  {"scale", Vec3{1, 2, 3}}, {"rotate", Vec3{0, 0, 90}}, {"density", rho}});
  const double m = rho * 4 * M_PI / 3 * a * b * c;
  EXPECT_NEAR(body.mass() / m, 1, 1e-12);
  // Ascending: about the longest axis (z) m (a^2 + b^2) / 5, then m (a^2 + c^2) / 5, m (b^2 + c^2) / 5.
  EXPECT_NEAR(body.moments()[0], m * (a * a + b * b) / 5, 1e-12);
  EXPECT_NEAR(body.moments()[1], m * (a * a + c * c) / 5, 1e-12);
  EXPECT_NEAR(body.moments()[2], m * (b * b + c * c) / 5, 1e-12);
}

TEST(Body, ACylindersInertiaAboutItsAxisIsHalfMrSquared) {
  const double rho = 1000, r = 0.05, L = 0.4;
  const RigidBody body = body_of({{"shape", std::string("cylinder")}, {"base", Vec3{-0.2, 0, 0}},
                                  {"top", Vec3{0.2, 0, 0}}, {"radius", r}, {"translate", Vec3{0.1, 0.2, 0.3}},
                                  {"density", rho}});
  const double m = rho * M_PI * r * r * L;
  EXPECT_NEAR(body.moments()[0], m * r * r / 2, 1e-12);
  EXPECT_NEAR(body.moments()[2], m * (3 * r * r + L * L) / 12, 1e-12);
  EXPECT_NEAR(body.position()[0], 0.1, 1e-15);
  EXPECT_NEAR(body.position()[2], 0.3, 1e-15);
}

TEST(Body, AGivenMassAndInertiaAreTaken) {
  const RigidBody body = body_of({{"shape", std::string("box")}, {"lo", Vec3{0, 0, 0}}, {"hi", Vec3{0.1, 0.1, 0.1}},
                                  {"mass", 2.0}, {"center_of_mass", Vec3{0.05, 0.05, 0.02}},
                                  {"inertia", Vec3{0.01, 0.02, 0.025}}});
  EXPECT_EQ(body.mass(), 2.0);
  EXPECT_EQ(body.position()[2], 0.02);
  EXPECT_NEAR(body.moments()[0], 0.01, 1e-15);
  EXPECT_NEAR(body.moments()[2], 0.025, 1e-15);
}

// Out of the water (the fluid is a small block in a far corner), a box released at t = 0.01 s
// falls freely: z = z0 - g (t - 0.01)^2 / 2, exactly for the Verlet kicks; a second box held to
// heave, given a sideways velocity and a spin, keeps its x, y and turn.
TEST(Body, OutOfTheWaterABodyFallsFreely) {
  Simulation sim;
  corner_scene(sim);
  sim.add_fix(fix("free", "solid", {{"shape", std::string("box")}, {"lo", Vec3{0.2, 0.05, 0.3}},
                                    {"hi", Vec3{0.3, 0.15, 0.35}}, {"density", 700.0}, {"hold", 0.01}}));
  sim.add_fix(fix("heave", "solid", {{"shape", std::string("sphere")}, {"center", Vec3{0.1, 0.1, 0.3}},
                                     {"radius", 0.04}, {"density", 700.0}, {"velocity", Vec3{1, 2, 0.5}},
                                     {"angular_velocity", Vec3{3, 0, 1}}, {"free_translation", Vec3{0, 0, 1}},
                                     {"free_rotation", Vec3{0, 0, 0}}}));
  sim.run(105);  // 0.21 s
  const double t = sim.time() - 0.01, g = 9.81;
  const auto& free = dynamics_of(sim, "free").body();
  EXPECT_NEAR(free.position()[2], 0.325 - g * t * t / 2, 1e-12);
  EXPECT_NEAR(free.velocity()[2], -g * t, 1e-12);
  EXPECT_EQ(free.position()[0], 0.25);
  const auto& heave = dynamics_of(sim, "heave");
  const double T = sim.time();
  EXPECT_NEAR(heave.body().position()[2], 0.3 + 0.5 * T - g * T * T / 2, 1e-12);
  EXPECT_EQ(heave.body().position()[0], 0.1);
  EXPECT_EQ(heave.body().position()[1], 0.1);
  EXPECT_EQ(heave.rotation()[0], 0);
  EXPECT_EQ(heave.rotation()[2], 0);
}

TEST(Body, BadParametersAreRefusedByName) {
  const GivenParams box = {{"shape", std::string("box")}, {"lo", Vec3{0, 0, 0}}, {"hi", Vec3{0.1, 0.1, 0.1}}};
  auto with = [&](GivenParams more) {
    GivenParams p = box;
    p.insert(p.end(), more.begin(), more.end());
    return p;
  };
  EXPECT_ERROR_NAMING(fix("b", "solid", with({{"density", 500.0}, {"mass", 1.0}})), "'density'", "not both");
  EXPECT_ERROR_NAMING(fix("b", "solid", with({{"density", -5.0}})), "'density'", "must be in");
  EXPECT_ERROR_NAMING(fix("b", "solid", with({{"velocity", Vec3{1, 0, 0}}})), "'velocity'", "'density' or a 'mass'");
  EXPECT_ERROR_NAMING(fix("b", "solid", with({{"density", 500.0}, {"free_rotation", Vec3{1, 1, 0}}})),
                      "'free_rotation'", "one, or none");
  EXPECT_ERROR_NAMING(fix("b", "solid", with({{"density", 500.0}, {"free_rotation", Vec3{0.5, 0, 0}}})),
                      "'free_rotation'", "1 (free) or 0");
  EXPECT_ERROR_NAMING(fix("b", "solid", with({{"density", 500.0}, {"hinge", Vec3{0, 0, 0}}})), "'hinge'",
                      "exactly one rotation");
  EXPECT_ERROR_NAMING(fix("b", "solid", with({{"mass", 1.0}, {"inertia", Vec3{0.01, 0.01, 0.05}}})), "'inertia'",
                      "exceeds the sum");
  EXPECT_ERROR_NAMING(fix("b", "solid", with({{"mass", 1.0}, {"inertia", Vec3{0.01, 0.01, 0.01}},
                                              {"inertia_products", Vec3{0.02, 0, 0}}})),
                      "'inertia'", "not positive definite");
  EXPECT_ERROR_NAMING(fix("b", "solid", with({{"density", 500.0}, {"fluid", std::string("inside")}})), "'mass'",
                      "container");
  EXPECT_ERROR_NAMING(fix("b", "solid", {{"shape", std::string("plane")}, {"point", Vec3{0, 0, 0}},
                                         {"normal", Vec3{0, 0, 1}}, {"density", 500.0}}),
                      "plane", "cannot move");
}

// Archimedes in a slab 0.4 m long and 5 spacings wide (1 cm), 0.15 m deep: a box 0.1 m tall
// across the slab's width, held to heave, is released after 0.5 s at its expected draft.
class Archimedes : public ::testing::TestWithParam<std::tuple<std::string, double>> {};

TEST_P(Archimedes, ABoxFloatsAtItsDraftWithoutDrift) {
  const auto& [solver, relative] = GetParam();
  const double L = 0.4, W = 0.05, depth = 0.15, a = 0.1, s = 0.01, g = 9.81;
  Simulation sim;
  sim.set_domain(Domain{{0, 0, 0}, {L, W, 0.3}});
  sim.set_kernel_radius(2 * s);
  sim.set_timestep(0.4 * 2 * s / std::sqrt(2 * g * a));
  const double lo[3] = {0, 0, 0}, hi[3] = {L, W, depth}, v[3] = {0, 0, 0};
  add_lattice(sim, lo, hi, s, v);
  sim.add_fix(fix("gravity", "gravity"));
  if (solver == "pbf") {
    sim.add_fix(fix("pbf", "pbf"));
    sim.add_fix(fix("xsph", "xsph"));
  } else {
    sim.add_fix(fix("integrator", "leapfrog"));
    sim.add_fix(fix("wcsph", "wcsph"));
    sim.add_fix(fix("viscosity", "sph_viscosity"));
    sim.add_fix(fix("cfl", "cfl"));
  }
  sim.add_fix(fix("walls", "box"));
  const double bottom = depth - relative * a;
  sim.add_fix(fix("float", "solid", {{"shape", std::string("box")}, {"lo", Vec3{L / 2 - a / 2, 0, bottom}},
                                     {"hi", Vec3{L / 2 + a / 2, W, bottom + a}}, {"density", relative * 1000},
                                     {"hold", 0.5}, {"free_translation", Vec3{0, 0, 1}},
                                     {"free_rotation", Vec3{0, 0, 0}}}));
  sim.add_compute(StyleRegistry::builtin().make_compute(
      "level", "gauge", {{"points", Points{{0.03, W / 2, 0}, {L - 0.03, W / 2, 0}}}}));
  sim.run_until(2.0);
  // Means over [2, 3] s and [3, 4] s, sampled every 0.02 s.
  double z[2] = {0, 0}, level = 0;
  int samples[2] = {0, 0};
  std::vector<double> gauge;
  for (int k = 0; k < 100; ++k) {
    sim.run_until(2.0 + 0.02 * (k + 1));
    z[k / 50] += dynamics_of(sim, "float").body().position()[2];
    ++samples[k / 50];
    if (k >= 50) {
      sim.find_compute("level")->evaluate(sim, gauge);
      level += 0.5 * (gauge[0] + gauge[1]);
    }
  }
  const double rest = z[1] / samples[1], draft = level / samples[1] - (rest - a / 2);
  EXPECT_NEAR(draft / (relative * a), 1, 0.03) << "draft " << draft << " m, level " << level / samples[1];
  EXPECT_NEAR(z[0] / samples[0], rest, 1e-3);
}

INSTANTIATE_TEST_SUITE_P(BothSolvers, Archimedes,
                         ::testing::Values(std::make_tuple("pbf", 0.5), std::make_tuple("pbf", 0.75),
                                           std::make_tuple("wcsph", 0.5)),
                         [](const auto& info) {
                           return std::get<0>(info.param) + "_" +
                                  std::to_string(int(std::round(100 * std::get<1>(info.param))));
                         });

// The closed form's sphere (../shared/validation/floating_body_analytic_checks.csv: the
// submerged cap pi h^2 (3R - h) / 3 holds m / rho, so h = R at half the water's density): a
// quarter of a sphere R = 6 spacings on the corner x = y = 0 (two symmetry planes), of a
// quarter of the mass, held to heave, floats with its centre at the water level within 3% of R
// (the fluid's force on a sphere of 6 spacings is 2% short of Archimedes': about 1% of R deeper).
TEST(Body, AHalfDenseSphereFloatsWithItsCentreAtTheLevel) {
  const double L = 0.25, depth = 0.15, R = 0.06, s = 0.01, g = 9.81;
  Simulation sim;
  sim.set_domain(Domain{{0, 0, 0}, {L, L, 0.3}});
  sim.set_kernel_radius(2 * s);
  sim.set_timestep(0.4 * 2 * s / std::sqrt(2 * g * R));
  const double lo[3] = {0, 0, 0}, hi[3] = {L, L, depth}, v[3] = {0, 0, 0};
  add_lattice(sim, lo, hi, s, v);
  sim.add_fix(fix("gravity", "gravity"));
  sim.add_fix(fix("pbf", "pbf"));
  sim.add_fix(fix("xsph", "xsph"));
  sim.add_fix(fix("walls", "box"));
  const double quarter_mass = 0.5 * 1000 * 4 * M_PI / 3 * R * R * R / 4;
  sim.add_fix(fix("ball", "solid", {{"shape", std::string("sphere")}, {"center", Vec3{0, 0, depth}}, {"radius", R},
                                    {"mass", quarter_mass}, {"hold", 0.5}, {"free_translation", Vec3{0, 0, 1}},
                                    {"free_rotation", Vec3{0, 0, 0}}}));
  sim.add_compute(StyleRegistry::builtin().make_compute(
      "level", "gauge", {{"points", Points{{L - 0.03, 0.03, 0}, {0.03, L - 0.03, 0}, {L - 0.03, L - 0.03, 0}}}}));
  sim.run_until(2.0);
  double z = 0, level = 0;
  std::vector<double> gauge;
  for (int k = 0; k < 50; ++k) {  // means over [2, 3] s
    sim.run_until(2.0 + 0.02 * (k + 1));
    z += dynamics_of(sim, "ball").body().position()[2] / 50;
    sim.find_compute("level")->evaluate(sim, gauge);
    level += (gauge[0] + gauge[1] + gauge[2]) / 3 / 50;
  }
  EXPECT_NEAR((level - z) / R, 0, 0.03) << "centre " << z << " m, level " << level << " m";
}

// Contact: in air, a plank falls on the floor, a block on the plank, a ball rolls off the block
// to the floor; after a second each rests, one particle spacing (the contact gap) above what
// it lies on, its speed below 1e-4 m/s (gravity's half kick, 1e-2 m/s, taken back by the
// contact, not left in the velocity).
TEST(Body, BodiesComeToRestOnTheFloorAndOnEachOther) {
  Simulation sim;
  corner_scene(sim);
  sim.add_fix(fix("plank", "solid", {{"shape", std::string("box")}, {"lo", Vec3{0.15, 0.05, 0.05}},
                                     {"hi", Vec3{0.35, 0.15, 0.08}}, {"density", 500.0}}));
  sim.add_fix(fix("block", "solid", {{"shape", std::string("box")}, {"lo", Vec3{0.2, 0.07, 0.2}},
                                     {"hi", Vec3{0.26, 0.13, 0.26}}, {"density", 800.0}}));
  sim.run_until(1.0);
  const auto& plank = dynamics_of(sim, "plank").body();
  const auto& block = dynamics_of(sim, "block").body();
  const double s = 0.01;  // the spacing
  EXPECT_NEAR(plank.position()[2], s + 0.015, 1e-3 * s);
  EXPECT_NEAR(block.position()[2], 0.015 + 0.015 + s + 0.03 + s, 1e-3 * s);
  for (const auto* b : {&plank, &block}) {
    EXPECT_LT(std::hypot(b->velocity()[0], b->velocity()[1], b->velocity()[2]), 1e-4);
    EXPECT_LT(std::hypot(b->angular_velocity()[0], b->angular_velocity()[1], b->angular_velocity()[2]), 1e-3);
  }
  // At rest, the contacts bear each body's weight (the plank: the floor's push less the
  // block's), over a step, with what the water bears (the corner block has spread over the
  // floor by now, a film under the plank): within 1e-4 of the weight (the rest speed's
  // change over a step, 1e-4 m/s against g dt = 0.02 m/s, bounds the imbalance at 5e-3).
  for (const char* name : {"plank", "block"}) {
    const auto& d = dynamics_of(sim, name);
    const double weight = d.body().mass() * 9.81;
    EXPECT_NEAR((d.contact_force()[2] + d.fluid_load()[2]) / weight, 1, 5e-3) << name;
    EXPECT_NEAR(d.contact_force()[0] + d.fluid_load()[0], 0, 5e-3 * weight) << name;
  }
}

// A body that must sink sinks: a ball of twice the water's density, released at mid-depth in a
// tank 0.15 m deep (PBF), reaches the floor within 0.5 s and rests there, a spacing above it,
// its vertical speed below 1 mm/s for the next half second. (The water its fall stirred still
// moves at about 1 cm/s, and rolls the ball on the floor: it stays within 2 mm of where it lies.)
TEST(Body, AHeavyBallSinksToTheFloorAndRests) {
  Simulation sim;
  const double s = 0.01, r = 0.03;
  sim.set_domain(Domain{{0, 0, 0}, {0.2, 0.2, 0.25}});
  sim.set_kernel_radius(2 * s);
  sim.set_timestep(0.004);
  const double lo[3] = {0, 0, 0}, hi[3] = {0.2, 0.2, 0.15}, v[3] = {0, 0, 0};
  add_lattice(sim, lo, hi, s, v);
  sim.add_fix(fix("gravity", "gravity"));
  sim.add_fix(fix("pbf", "pbf"));
  sim.add_fix(fix("xsph", "xsph"));
  sim.add_fix(fix("walls", "box"));
  sim.add_fix(fix("ball", "solid", {{"shape", std::string("sphere")}, {"center", Vec3{0.1, 0.1, 0.08}},
                                    {"radius", r}, {"density", 2000.0}, {"hold", 0.2}}));
  sim.run_until(0.7);
  const auto& ball = dynamics_of(sim, "ball").body();
  EXPECT_NEAR(ball.position()[2], r + s, 0.05 * s);
  const auto lies = ball.position();
  for (int k = 0; k < 10; ++k) {
    sim.run_until(0.7 + 0.05 * (k + 1));
    EXPECT_NEAR(ball.position()[2], r + s, 0.05 * s);
    EXPECT_LT(std::abs(ball.velocity()[2]), 1e-3);
    EXPECT_LT(std::hypot(ball.position()[0] - lies[0], ball.position()[1] - lies[1]), 0.2 * s);
  }
}

namespace {

// A bob of mass m (a box 10 x 10 x 5 cm, its top's centre at z = 0.25 m) held to heave, hung
// from a spring of stiffness k and damping c whose top is 0.1 m above it (its rest length), at
// 200 steps a period of 2 pi sqrt(m / k).
void hang_bob(Simulation& sim, double m, double k, double c) {
  corner_scene(sim);
  sim.set_timestep(2 * M_PI * std::sqrt(m / k) / 200);
  sim.add_fix(fix("bob", "solid", {{"shape", std::string("box")}, {"lo", Vec3{0.2, 0.05, 0.2}},
                                   {"hi", Vec3{0.3, 0.15, 0.25}}, {"mass", m}, {"free_translation", Vec3{0, 0, 1}},
                                   {"free_rotation", Vec3{0, 0, 0}}}));
  sim.add_fix(fix("line", "spring", {{"body", std::string("bob")}, {"at", Vec3{0.25, 0.1, 0.25}},
                                     {"to", Vec3{0.25, 0.1, 0.35}}, {"stiffness", k}, {"damping", c}}));
}

}  // namespace

// A spring: a box of 1.2 kg hung in air from a fixed point on a spring of 300 N/m, damping 0,
// held to heave, released at the spring's rest length, oscillates about the stretch m g / k at
// the period 2 pi sqrt(m / k) (within 1e-3: the Verlet's phase error (w dt)^2 / 24 at 200
// steps a period), and the spring compute reads the tension k (L - L0). Two boxes joined by a
// spring, out of gravity, pushed apart: their momentum stays zero to round-off.
TEST(Body, ASpringHoldsABodyAtItsStretchAndPeriod) {
  const double m = 1.2, k = 300, g = 9.81, T = 2 * M_PI * std::sqrt(m / k);
  Simulation sim;
  hang_bob(sim, m, k, 0);
  sim.add_compute(StyleRegistry::builtin().make_compute("s", "spring_tension", {{"fix", std::string("line")}}));
  std::vector<double> crossings, values;
  const double rest = 0.225 - m * g / k;  // the centre's equilibrium
  double last = 0.225 - rest, lowest = 1;
  for (int step = 0; step < 1000; ++step) {
    sim.run(1);
    const double z = dynamics_of(sim, "bob").body().position()[2] - rest;
    lowest = std::min(lowest, z + rest);
    if ((z < 0) != (last < 0)) crossings.push_back(sim.time() - sim.timestep() * z / (z - last));
    last = z;
  }
  const double period = 2 * (crossings.back() - crossings.front()) / double(crossings.size() - 1);
  EXPECT_NEAR(period / T, 1, 1e-3);
  EXPECT_NEAR(lowest, 0.225 - 2 * m * g / k, 1e-3 * m * g / k);  // it swings down twice the stretch
  sim.find_compute("s")->evaluate(sim, values);
  const double length = 0.35 - (dynamics_of(sim, "bob").body().position()[2] + 0.025);
  EXPECT_NEAR(values[1], length, 1e-12);
  EXPECT_NEAR(values[0], k * (length - 0.1), 1e-9);
  EXPECT_NEAR(values[4], values[0], 1e-12);

  Simulation pair;
  corner_block(pair);
  pair.add_fix(fix("pbf", "pbf"));
  pair.add_fix(fix("walls", "box"));
  pair.add_fix(fix("a", "solid", {{"shape", std::string("box")}, {"lo", Vec3{0.1, 0.05, 0.2}},
                                  {"hi", Vec3{0.15, 0.1, 0.25}}, {"mass", 1.0}, {"velocity", Vec3{-0.1, 0, 0.05}}}));
  pair.add_fix(fix("b", "solid", {{"shape", std::string("box")}, {"lo", Vec3{0.25, 0.05, 0.2}},
                                  {"hi", Vec3{0.3, 0.15, 0.25}}, {"mass", 2.0}, {"velocity", Vec3{0.05, 0, -0.025}}}));
  pair.add_fix(fix("tie", "spring", {{"body", std::string("a")}, {"at", Vec3{0.15, 0.075, 0.25}}, {"to_body", std::string("b")},
                                     {"to", Vec3{0.25, 0.1, 0.2}}, {"stiffness", 50.0}, {"damping", 0.5}}));
  pair.run(300);
  const auto &a = dynamics_of(pair, "a").body(), &b = dynamics_of(pair, "b").body();
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(a.velocity()[c] + 2 * b.velocity()[c], 0, 1e-15) << c;
  EXPECT_GT(std::abs(a.velocity()[0] + 0.1), 0.01);  // the spring has acted
}

// The same bob with a damper of c = 2 N s/m: it oscillates about the stretch with its
// amplitude decaying as exp(-c t / 2m) (gamma = 0.83 /s); over the first five swings the
// peaks fall by that within 1% (the damper reads the half-step's velocity: an O(dt) lag).
TEST(Body, ADampedSpringsSwingDecaysAtCOverTwoM) {
  const double m = 1.2, k = 300, c = 2, g = 9.81;
  Simulation sim;
  hang_bob(sim, m, k, c);
  const double rest = 0.225 - m * g / k;
  std::vector<double> peaks, times;
  double before = 0, last = 0;
  for (int step = 0; step < 1100; ++step) {
    sim.run(1);
    const double z = dynamics_of(sim, "bob").body().position()[2] - rest;
    if (step > 1 && std::abs(last) > std::abs(before) && std::abs(last) >= std::abs(z)) {
      peaks.push_back(std::abs(last));
      times.push_back(sim.time() - sim.timestep());
    }
    before = last;
    last = z;
  }
  ASSERT_GE(peaks.size(), 10u);
  const double gamma = std::log(peaks[0] / peaks[9]) / (times[9] - times[0]);
  EXPECT_NEAR(gamma / (c / (2 * m)), 1, 0.01);
}

// A crate on a platform a motion lifts at 0.1 m/s from 0.05 s: the crate rides up on it, a
// spacing (its contact gap) above it within a tenth of a spacing, at its speed within 1%; and
// a crate in the path of a plate a motion pushes along x at 0.2 m/s is pushed ahead of it.
TEST(Body, ASolidAMotionMovesCarriesAndPushesBodies) {
  Simulation sim;
  corner_scene(sim);
  sim.add_fix(fix("crate", "solid", {{"shape", std::string("box")}, {"lo", Vec3{0.2, 0.07, 0.13}},
                                     {"hi", Vec3{0.3, 0.13, 0.17}}, {"density", 700.0}}));
  using Key = Keyframes::Key;
  auto keys = [](const Vec3& velocity) {  // at rest until 0.05 s, then moving at `velocity`
    return std::make_shared<Keyframes>(
        std::vector<Key>{{0, Pose{}}, {0.05, Pose{}}, {10.05, Pose{{10 * velocity[0], 0, 10 * velocity[2]}, {0, 0, 0}}}},
        Keyframes::Interpolation::linear, "test");
  };
  sim.add_fix(fix("platform", "solid", {{"shape", std::string("box")}, {"lo", Vec3{0.15, 0.05, 0.1}},
                                        {"hi", Vec3{0.35, 0.15, 0.12}}, {"motion", MotionPtr(keys({0, 0, 0.1}))}}));
  sim.add_fix(fix("block", "solid", {{"shape", std::string("box")}, {"lo", Vec3{0.2, 0.07, 0.01}},
                                     {"hi", Vec3{0.25, 0.13, 0.05}}, {"density", 700.0}}));
  sim.add_fix(fix("plate", "solid", {{"shape", std::string("box")}, {"lo", Vec3{0.15, 0.03, 0.02}},
                                     {"hi", Vec3{0.18, 0.17, 0.09}}, {"motion", MotionPtr(keys({0.2, 0, 0}))}}));
  sim.run(150);  // 0.3 s
  const auto& crate = dynamics_of(sim, "crate").body();
  const double top = 0.12 + 0.1 * (sim.time() - 0.05);
  EXPECT_NEAR(crate.position()[2] - 0.02 - top, 0.01, 0.001);
  EXPECT_NEAR(crate.velocity()[2] / 0.1, 1, 0.01);
  const auto& block = dynamics_of(sim, "block").body();
  const double face = 0.18 + 0.2 * (sim.time() - 0.05);
  EXPECT_NEAR(block.position()[0] - 0.025 - face, 0.01, 0.001);
  EXPECT_NEAR(block.velocity()[0] / 0.2, 1, 0.01);
}
