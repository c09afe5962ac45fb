// Bodies held by joints (engine/bodies/rigid_body.*, the `solid` fix's hinge, pivot and slider).
//  - A hinged body is a physical pendulum: at small amplitude its period is
//    2 pi sqrt(I_p / (m g d)), I_p = I_c + m d^2 about the hinge, d the centre's distance.
//  - On a pivot (a ball joint) it is a free rotor about the pivot under gravity: swung in a
//    principal plane it keeps to it at the hinge's period; swung anyhow, its centre stays at
//    its distance from the pivot and the angular momentum about the vertical through the pivot
//    is kept to round-off (gravity has no moment about it), the energy within the splitting's
//    O(dt^2) error.
//  - A joint's reaction is the `body` compute's held force: a hanging gate's and a hanging
//    ball's is their weight; a block on a slider along (1, 0, -1) slides at g / sqrt(2), its
//    slider pushing back m g / sqrt(2) across the slide.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "body_scenes.hpp"
#include "test_util.hpp"

using namespace pbf;
using pbf::test::corner_scene;
using pbf::test::dynamics_of;
using pbf::test::fix;

namespace {

using Vec = RigidBody::Vec;

// A box a x b x c of mass m, its centre at the origin, its edges along the axes.
MassProperties block(double m, double a, double b, double c) {
  MassProperties p;
  p.mass = m;
  p.center = {0, 0, 0};
  p.inertia = {{{m * (b * b + c * c) / 12, 0, 0}, {0, m * (a * a + c * c) / 12, 0}, {0, 0, m * (a * a + b * b) / 12}}};
  return p;
}

// Velocity Verlet under the weight, as the solid fix steps a body.
void swing(RigidBody& body, double g, double dt) {
  const Vec weight{0, 0, -body.mass() * g};
  body.kick(weight, {0, 0, 0}, dt / 2);
  body.drift(dt);
  body.kick(weight, {0, 0, 0}, dt / 2);
}

// The period of the angular velocity's component k, by its zero crossings over `steps` steps.
double period_of(RigidBody& body, int k, double g, double dt, int steps) {
  std::vector<double> crossings;
  double last = body.angular_velocity()[k];
  for (int step = 0; step < steps; ++step) {
    swing(body, g, dt);
    const double w = body.angular_velocity()[k];
    if ((w < 0) != (last < 0)) crossings.push_back((step + 1) * dt - dt * w / (w - last));
    last = w;
  }
  return 2 * (crossings.back() - crossings.front()) / double(crossings.size() - 1);
}

}  // namespace

// A box 0.02 x 0.1 x 0.3 m hinged at a point 0.1 m above its centre, swinging about y: at an
// amplitude of 0.01 rad the period is the small-angle one's within 1e-5 (amplitude^2 / 16), and
// the energy stays within its O(dt^2) error (1e-5) over 20 swings at 200 steps a swing.
TEST(Joint, AHingedBoxSwingsAsAPhysicalPendulum) {
  const double g = 9.81, d = 0.1;
  const MassProperties p = block(1.5, 0.02, 0.1, 0.3);
  RigidBody body(p);
  RigidBody::Freedom hinge;
  hinge.turn = RigidBody::Freedom::Turn::about_axis;
  hinge.axis = 1;
  hinge.pinned = true;
  hinge.pivot = {0, 0, d};
  body.restrict(hinge);
  const double Ip = p.inertia[1][1] + p.mass * d * d, T = 2 * M_PI * std::sqrt(Ip / (p.mass * g * d));
  body.set_angular_velocity({0, 0.01 * 2 * M_PI / T, 0});  // through the bottom at amplitude 0.01
  auto energy = [&] { return body.kinetic_energy() + p.mass * g * body.position()[2]; };
  const double e0 = energy();
  EXPECT_NEAR(period_of(body, 1, g, T / 200, 20 * 200) / T, 1, 1e-4);
  EXPECT_NEAR(std::hypot(body.position()[0], body.position()[2] - d), d, 1e-14);
  EXPECT_NEAR(body.position()[1], 0, 1e-15);
  EXPECT_NEAR((energy() - e0) / (p.mass * g * d * 0.01 * 0.01 / 2), 0, 2e-3);  // of the swing's energy
}

// The hinge's box on a pivot 0.1 m above its centre, swung about y (a principal axis) at
// 0.01 rad: it swings in the x-z plane only, at the hinge's period within 1e-4.
TEST(Joint, ABallJointSwungInAPrincipalPlaneSwingsAsTheHinge) {
  const double g = 9.81, d = 0.1;
  const MassProperties p = block(1.5, 0.02, 0.1, 0.3);
  RigidBody body(p);
  RigidBody::Freedom pivot;
  pivot.pinned = true;
  pivot.pivot = {0, 0, d};
  body.restrict(pivot);
  const double Ip = p.inertia[1][1] + p.mass * d * d, T = 2 * M_PI * std::sqrt(Ip / (p.mass * g * d));
  body.set_angular_velocity({0, 0.01 * 2 * M_PI / T, 0});
  EXPECT_NEAR(period_of(body, 1, g, T / 200, 20 * 200) / T, 1, 1e-4);
  EXPECT_NEAR(body.position()[1], 0, 1e-15);
  EXPECT_NEAR(body.angular_velocity()[0], 0, 1e-15);
  EXPECT_NEAR(body.angular_velocity()[2], 0, 1e-15);
}

// An asymmetric block on a pivot off all its axes, thrown round it at 2 rad/s about a tilted
// axis, 400 steps a second for 10 s: the pivot's point of the body stays still, the centre at
// its distance; L about the vertical through the pivot is kept to round-off; the energy within
// 1e-4 of the motion's (the splitting's O(dt^2) error: it does not drift).
TEST(Joint, ABallJointedBodyKeepsItsArmAndItsVerticalMomentum) {
  const double g = 9.81;
  RigidBody body(block(2.0, 0.05, 0.12, 0.3));
  RigidBody::Freedom pivot;
  pivot.pinned = true;
  pivot.pivot = {0.03, -0.02, 0.12};
  body.restrict(pivot);
  body.set_angular_velocity({0.6, 1.2, 1.5});
  const Vec r0{-0.03, 0.02, -0.12};
  const double arm = std::sqrt(r0[0] * r0[0] + r0[1] * r0[1] + r0[2] * r0[2]);
  auto vertical_momentum = [&] { return body.angular_momentum()[2]; };  // a ball joint's: about the pivot
  auto energy = [&] { return body.kinetic_energy() + body.mass() * g * body.position()[2]; };
  const double Lz0 = vertical_momentum(), e0 = energy(), scale = body.kinetic_energy() + body.mass() * g * arm;
  const double dt = 1.0 / 400;
  double worst = 0, sideways = 0;
  for (int step = 0; step < 4000; ++step) {
    swing(body, g, dt);
    const Vec x = body.position(), at_pivot = body.velocity_at(pivot.pivot);
    ASSERT_NEAR(std::hypot(x[0] - 0.03, x[1] + 0.02, x[2] - 0.12), arm, 1e-14) << step;
    ASSERT_NEAR(std::hypot(at_pivot[0], at_pivot[1], at_pivot[2]), 0, 1e-13) << step;
    worst = std::max(worst, std::abs(energy() - e0) / scale);
    sideways = std::max(sideways, std::abs(x[1] + 0.02));
  }
  EXPECT_NEAR(vertical_momentum(), Lz0, 1e-12 * std::abs(Lz0));
  EXPECT_LT(worst, 1e-4);
  EXPECT_GT(sideways, 0.01);  // it swung out of its starting plane
}

// A hinged gate hanging at rest below its hinge: the hinge holds its weight (the held force's
// z is m g, to round-off); its angle stays 0.
TEST(Joint, AHingeHoldsAHangingGatesWeight) {
  Simulation sim;
  corner_scene(sim);
  sim.add_fix(fix("gate", "solid", {{"shape", std::string("box")}, {"lo", Vec3{0.2, 0.05, 0.2}},
                                    {"hi", Vec3{0.22, 0.15, 0.3}}, {"density", 700.0},
                                    {"free_rotation", Vec3{0, 1, 0}}, {"hinge", Vec3{0.21, 0.1, 0.3}}}));
  sim.run(50);
  const auto& gate = dynamics_of(sim, "gate");
  const double weight = gate.body().mass() * 9.81;
  EXPECT_NEAR(gate.held_force()[2] / weight, 1, 1e-9);
  EXPECT_NEAR(gate.held_force()[0] / weight, 0, 1e-9);
  EXPECT_NEAR(gate.rotation()[1], 0, 1e-12);
}


// A ball hanging 0.05 m below its ball joint, at rest: the joint holds its weight.
TEST(Joint, ABallJointHoldsAHangingBallsWeight) {
  Simulation sim;
  corner_scene(sim);
  sim.add_fix(fix("ball", "solid", {{"shape", std::string("sphere")}, {"center", Vec3{0.25, 0.1, 0.25}},
                                    {"radius", 0.03}, {"density", 700.0}, {"ball_joint", Vec3{0.25, 0.1, 0.3}}}));
  sim.run(50);
  const auto& ball = dynamics_of(sim, "ball");
  const double weight = ball.body().mass() * 9.81;
  EXPECT_NEAR(ball.held_force()[2] / weight, 1, 1e-9);
  EXPECT_NEAR(ball.body().position()[2], 0.25, 1e-12);
}

// A block on a slider down the slope (1, 0, -1), released at 0.01 s: it slides s = g t^2 /
// (2 sqrt 2) along it (the Verlet kicks of a constant force are exact), does not turn, and the
// slider holds it with m g / sqrt(2) across the slope, (m g / 2)(1, 0, 1).
TEST(Joint, ABlockOnASlopingSliderSlidesAtGOverRootTwo) {
  Simulation sim;
  corner_scene(sim);
  sim.add_fix(fix("block", "solid", {{"shape", std::string("box")}, {"lo", Vec3{0.1, 0.05, 0.3}},
                                     {"hi", Vec3{0.15, 0.15, 0.35}}, {"density", 700.0}, {"hold", 0.01},
                                     {"slider", Vec3{2, 0, -2}}}));
  sim.run(80);
  const double t = sim.time() - 0.01, g = 9.81, s = g * t * t / (2 * std::sqrt(2.0));
  const auto& block = dynamics_of(sim, "block");
  EXPECT_NEAR(block.body().position()[0], 0.125 + s / std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(block.body().position()[2], 0.325 - s / std::sqrt(2.0), 1e-12);
  EXPECT_EQ(block.body().position()[1], block.placed_center()[1]);
  for (int a = 0; a < 3; ++a) EXPECT_EQ(block.rotation()[a], 0) << a;
  const double mg = block.body().mass() * g;
  EXPECT_NEAR(block.held_force()[0] / mg, 0.5, 1e-9);
  EXPECT_NEAR(block.held_force()[1] / mg, 0, 1e-9);
  EXPECT_NEAR(block.held_force()[2] / mg, 0.5, 1e-9);
}

// A ball on a ball joint, its arm along x, placed 5 mm from the wall x = 0.4 m (inside its
// contact gap of a spacing): the wall's contact at the point on the arm's line is one the body
// cannot answer along x (the joint holds that point's radial motion): it is the joint's to
// hold, and the ball stays put, pressed to the wall, rather than being thrown by the contact's
// 1 / K.
TEST(Joint, AContactAlongAJointsArmIsTheJointsToHold) {
  Simulation sim;
  corner_scene(sim);
  sim.add_fix(fix("ball", "solid", {{"shape", std::string("sphere")}, {"center", Vec3{0.365, 0.1, 0.3}},
                                    {"radius", 0.03}, {"density", 1500.0}, {"ball_joint", Vec3{0.255, 0.1, 0.3}}}));
  sim.run(20);
  const auto& ball = dynamics_of(sim, "ball").body();
  const Vec w = ball.angular_velocity();
  EXPECT_LT(std::hypot(w[0], w[1], w[2]), 1.0);  // a free swing would reach 3 rad/s
  EXPECT_NEAR(std::hypot(ball.position()[0] - 0.255, ball.position()[2] - 0.3), 0.11, 1e-9);
}

TEST(Joint, BadJointsAreRefusedByName) {
  const GivenParams box = {{"shape", std::string("box")}, {"lo", Vec3{0, 0, 0}}, {"hi", Vec3{0.1, 0.1, 0.1}},
                           {"density", 500.0}};
  auto with = [&](GivenParams more) {
    GivenParams p = box;
    p.insert(p.end(), more.begin(), more.end());
    return p;
  };
  EXPECT_ERROR_NAMING(fix("b", "solid", with({{"slider", Vec3{0, 0, 0}}})), "'slider'", "no length");
  EXPECT_ERROR_NAMING(fix("b", "solid", with({{"ball_joint", Vec3{0, 0, 0}}, {"free_rotation", Vec3{0, 1, 0}}})),
                      "'ball_joint'", "'hinge'");
  EXPECT_ERROR_NAMING(fix("b", "solid", with({{"ball_joint", Vec3{0, 0, 0}}, {"slider", Vec3{1, 0, 0}}})), "'slider'",
                      "one of");
  EXPECT_ERROR_NAMING(fix("b", "solid", with({{"slider", Vec3{1, 0, 0}}, {"free_translation", Vec3{1, 0, 0}}})),
                      "'free_translation'", "joint");
  EXPECT_ERROR_NAMING(fix("b", "solid", with({{"ball_joint", Vec3{0, 0, 0}}, {"free_rotation", Vec3{0, 0, 0}}})),
                      "'ball_joint'", "turns freely");
}
