// Rigid bodies (engine/bodies): the mass properties of a closed mesh, and the free rotation.
// The figures are the closed-form rows of ../shared/validation/floating_body_analytic_checks.csv
// ("torque_free"): a cuboid 0.1 x 0.2 x 0.3 m of 1 kg has I = m (b^2 + c^2) / 12 etc. about its
// centre (the polyhedral integrals are exact for it: round-off only); spun about its axis of
// largest or smallest moment and nudged, it wobbles at Omega / w1 = sqrt((I1 - I2)(I1 - I3) /
// (I2 I3)) (0.69282 and 0.5547); a symmetric plate 0.2 x 0.2 x 0.1 m precesses in its own frame
// at w3 (I3 - I1) / I1 = 0.6 w3. The splitting integrator keeps L to round-off and the energy
// within its O(dt^2) error; the issue asks, at 100 steps a turn over 1,000 turns, for L within
// 0.1% and the energy within 0.5%, and the rates within 0.5% (the scheme's phase error at
// w dt = 2 pi / 100 is of order (w dt)^2 / 12 = 0.3%).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "engine/bodies/mass_properties.hpp"
#include "engine/bodies/rigid_body.hpp"
#include "engine/core/error.hpp"
#include "engine/geometry/primitives.hpp"

using namespace pbf;

namespace {

using Vec = std::array<double, 3>;

double norm(const Vec& a) { return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }

// The cuboid of the checks (1 kg), its centre at c.
MassProperties cuboid(const Vec& c, const Vec& sides, double mass = 1.0) {
  const TriangleMesh mesh = box_mesh({c[0] - sides[0] / 2, c[1] - sides[1] / 2, c[2] - sides[2] / 2},
                                     {c[0] + sides[0] / 2, c[1] + sides[1] / 2, c[2] + sides[2] / 2});
  return mass_properties(mesh, mass / (sides[0] * sides[1] * sides[2]), "cuboid");
}

// The period of a body-frame component of the angular velocity (axis k) by its zero crossings
// over `turns` turns of dt = T / 100, T = 2 pi / |w|.
double wobble_period(RigidBody body, int k, double turns) {
  const double w = norm(body.angular_velocity()), dt = 2 * M_PI / w / 100;
  std::vector<double> crossings;
  double last = 0;
  for (long step = 0; step < long(turns * 100); ++step) {
    body.drift(dt);
    const Vec omega = body.orientation().conjugate().rotate(body.angular_velocity());
    if (step > 0 && (last < 0) != (omega[k] < 0)) crossings.push_back((step + 1) * dt - dt * omega[k] / (omega[k] - last));
    last = omega[k];
  }
  return 2 * (crossings.back() - crossings.front()) / double(crossings.size() - 1);
}

}  // namespace

TEST(MassProperties, OfABoxMeshAreTheCuboidsExactly) {
  const MassProperties p = cuboid({1, -2, 3}, {0.1, 0.2, 0.3});
  EXPECT_NEAR(p.volume, 0.006, 1e-15);
  EXPECT_NEAR(p.mass, 1.0, 1e-12);
  EXPECT_NEAR(p.center[0], 1, 1e-12);
  EXPECT_NEAR(p.center[1], -2, 1e-12);
  EXPECT_NEAR(p.center[2], 3, 1e-12);
  const double expected[3] = {0.010833333333333333, 0.008333333333333333, 0.004166666666666667};  // the csv's
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(p.inertia[i][j], i == j ? expected[i] : 0, 1e-12) << i << j;
  Vec moments;
  Matrix3 axes;
  principal_axes(p.inertia, moments, axes);
  EXPECT_NEAR(moments[0], expected[2], 1e-14);
  EXPECT_NEAR(moments[2], expected[0], 1e-14);
}

TEST(MassProperties, FindTheAxesOfATurnedBody) {
  TriangleMesh mesh = box_mesh({-0.05, -0.1, -0.15}, {0.05, 0.1, 0.15});
  const Quaternion turn = (Quaternion::about_axis(2, 0.7) * Quaternion::about_axis(0, -0.4)).normalized();
  for (auto& v : mesh.vertices) v = turn.rotate(v);
  const MassProperties p = mass_properties(mesh, 1 / 0.006, "turned cuboid");
  const RigidBody body(p);
  EXPECT_NEAR(body.moments()[0], 0.004166666666666667, 1e-12);
  EXPECT_NEAR(body.moments()[1], 0.008333333333333333, 1e-12);
  EXPECT_NEAR(body.moments()[2], 0.010833333333333333, 1e-12);
  // The axis of the smallest moment is the box's z (0.3 m) turned: +-.
  const Vec axis = body.orientation().rotate({1, 0, 0}), z = turn.rotate({0, 0, 1});
  EXPECT_NEAR(std::fabs(axis[0] * z[0] + axis[1] * z[1] + axis[2] * z[2]), 1, 1e-10);
}

TEST(MassProperties, RefuseAnOpenOrInsideOutMeshAndABadDensity) {
  TriangleMesh open = box_mesh({0, 0, 0}, {1, 1, 1});
  open.triangles.pop_back();
  EXPECT_THROW(mass_properties(open, 1000, "open"), Error);
  TriangleMesh inside_out = box_mesh({0, 0, 0}, {1, 1, 1});
  for (auto& t : inside_out.triangles) std::swap(t[1], t[2]);
  EXPECT_THROW(mass_properties(inside_out, 1000, "inside out"), Error);
  for (double density : {0.0, -1.0, std::nan(""), double(INFINITY)})
    EXPECT_THROW(mass_properties(box_mesh({0, 0, 0}, {1, 1, 1}), density, "box"), Error) << density;
}

TEST(RigidBody, AFreeAsymmetricBodyKeepsItsMomentumAndEnergyOver1000Turns) {
  RigidBody body(cuboid({0, 0, 0}, {0.1, 0.2, 0.3}));
  body.set_angular_velocity({2 * M_PI * 0.6, 2 * M_PI * 0.5, 2 * M_PI * 0.62});  // |w| about 1.7 turns/s, off every axis
  const Vec L0 = body.angular_momentum();
  const double E0 = body.kinetic_energy(), dt = 2 * M_PI / norm(body.angular_velocity()) / 100;
  double worst_energy = 0;
  for (long step = 0; step < 100000; ++step) {
    body.drift(dt);
    worst_energy = std::max(worst_energy, std::fabs(body.kinetic_energy() / E0 - 1));
  }
  const Vec L = body.angular_momentum();
  EXPECT_LT(norm({L[0] - L0[0], L[1] - L0[1], L[2] - L0[2]}) / norm(L0), 1e-3);
  EXPECT_LT(worst_energy, 5e-3);
  std::printf("energy within %.3g over 1000 turns\n", worst_energy);
}

TEST(RigidBody, WobblesAboutItsStableAxesAtTheRatesOfTheLinearisedEulerEquations) {
  const double I1 = 0.010833333333333333, I2 = 0.008333333333333333, I3 = 0.004166666666666667;
  for (int axis : {2, 0}) {  // body frame: 0 the smallest moment (the box's z), 2 the largest (its x)
    RigidBody body(cuboid({0, 0, 0}, {0.1, 0.2, 0.3}));
    Vec w{0.01, 0.01, 0.01};
    w[axis] = 2 * M_PI;  // one turn a second, nudged
    body.set_angular_velocity(body.orientation().rotate(w));
    const double period = wobble_period(body, axis == 2 ? 0 : 2, 60);
    const double a = axis == 2 ? I1 : I3, b = I2, c = axis == 2 ? I3 : I1;
    const double expected = 2 * M_PI / (2 * M_PI * std::sqrt((a - b) * (a - c) / (b * c)));
    EXPECT_NEAR(period, expected, 0.005 * expected) << "spin about body axis " << axis;
    std::printf("axis %d: wobble / spin %.5f (expected %.5f)\n", axis, 1 / period, 1 / expected);
  }
}

TEST(RigidBody, ASymmetricPlatePrecessesInItsFrameAtTheClosedFormRate) {
  RigidBody body(cuboid({0, 0, 0}, {0.2, 0.2, 0.1}));  // I1 = I2 = m (0.04 + 0.01) / 12, I3 = m 0.08 / 12
  const double w3 = 2 * M_PI;
  body.set_angular_velocity(body.orientation().rotate({0.3, 0, w3}));
  const double period = wobble_period(body, 0, 60);
  const double expected = 2 * M_PI / (0.6 * w3);  // the csv's 0.6
  EXPECT_NEAR(period, expected, 0.005 * expected);
}
