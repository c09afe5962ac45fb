// Vorticity confinement on flows whose answer is known: the SPH curl of a rigid rotation is
// twice its angular velocity (times the lattice's gradient norm kappa), sign included, and
// the confinement force pushes a flow along its own rotation where the vorticity grows.
// Each flow is set on a 14^3 block after the integrator's drift (tests/bulk_lattice.hpp), so
// the particles sit exactly on the lattice and the bulk's sums are lattice sums.
#include <gtest/gtest.h>

#include <cmath>

#include "bulk_lattice.hpp"
#include "engine/core/simulation.hpp"
#include "engine/registry/style_registry.hpp"

using namespace pbf;

namespace {

constexpr int kN[3] = {14, 14, 14};
constexpr double kS = 0.01, kH = 2 * kS;
// The largest |coordinate| of a site, in spacings: 6.5.
constexpr double kReach = (kN[0] - 1) / 2.0;

// The rounding of a pair sum here, relative to the sum of its terms' sizes (bulk_lattice.hpp).
const double kSumRounding = test::pair_sum_rounding(kReach);

// The block, the leapfrog (no forces: nothing moves), `field` set as the velocities after the
// integrator, then vorticity confinement of strength epsilon; one step of `dt`.
void run_one_step(Simulation& sim, double dt, double epsilon, test::SetVelocities::Field field) {
  test::centred_block(sim, kN, kS, dt);
  const auto& styles = StyleRegistry::builtin();
  sim.add_fix(styles.make_fix("integrator", "leapfrog", {}));
  sim.add_fix(std::make_unique<test::SetVelocities>(Stage::velocity_update, std::move(field)));
  sim.add_fix(styles.make_fix("vorticity", "vorticity", {{"epsilon", epsilon}}));
  sim.run(1);
}

}  // namespace

// v = Omega x r on the block. With r_j = x_j - x_i and gradW_ij = -g r_j,
//   omega_i = sum_j V gradW_ij x (v_j - v_i) = -sum_j V g r_j x (Omega x r_j)
//           = -sum_j V g (Omega r_j^2 - r_j (r_j . Omega)) = 3 kappa Omega - kappa Omega = 2 kappa Omega
// using sum_j V g r_a r_b = -kappa delta_ab (cubic symmetry). So in the bulk (2h deep: the
// neighbours' volumes need full neighbourhoods too) the field "vorticity" is 2 kappa Omega,
// all three components, to rounding. A curl of the wrong sign gives -2 kappa Omega.
TEST(Vorticity, ARigidRotationHasTwiceItsAngularVelocity) {
  const double omega[3] = {0.3, -0.5, 0.7};  // 1/s, every component different, both signs
  Simulation sim;
  run_one_step(sim, 1e-3, 0.05, [&](double x, double y, double z, double v[3]) {
    v[0] = omega[1] * z - omega[2] * y;
    v[1] = omega[2] * x - omega[0] * z;
    v[2] = omega[0] * y - omega[1] * x;
  });
  const auto& P = sim.particles();
  const auto field = P.find("vorticity");
  ASSERT_TRUE(field);
  const double kappa = test::gradient_norm(kS, sim.kernels());
  const double size = 2 * kappa * std::sqrt(omega[0] * omega[0] + omega[1] * omega[1] + omega[2] * omega[2]);
  // The terms' sizes add up to sum_j V |g| r^2 |Omega| = 3 kappa |Omega| = 1.5 |omega|.
  const double tolerance = 1.5 * size * kSumRounding;
  int bulk = 0;
  for (std::size_t i = 0; i < P.size(); ++i) {
    if (!test::in_bulk(kN, kS, 2 * kH, P.x()[i], P.y()[i], P.z()[i])) continue;
    ++bulk;
    for (int c = 0; c < 3; ++c)
      ASSERT_NEAR(P.data(*field, c)[i], 2 * kappa * omega[c], tolerance)
          << "particle at (" << P.x()[i] << ", " << P.y()[i] << ", " << P.z()[i] << "), component " << c;
  }
  EXPECT_EQ(bulk, 8 * 8 * 8);
}

// A shear flow whose vorticity grows along x: v = (0, a x + b x^2 / 2, 0), omega_z = a + b x
// > 0 over the block (b = a / (n s)). As a vortex whose centre lies toward +x and which turns
// counterclockwise, its flow here runs along -y; confinement must push along that, toward the
// stronger vorticity's rotation. On the lattice the curl is kappa (a + b x) z exactly (the
// quadratic part of v gives sums odd in r_x, zero by symmetry); its magnitude is linear in x,
// so eta = grad |omega| is kappa^2 b x exactly and N = +x. Then
//   a_i = epsilon h |omega| (N x omega) = -epsilon h kappa^2 (a + b x)^2 y,
// one step adds dt a_i to v_y. The bulk is 3h deep: eta reads the neighbours' |omega|, which
// need the 2h bulk. A reversed curl gives omega = -kappa (a + b x) z, the same N, and a push
// along +y; a reversed cross product the same.
// The same flow turned twice about (1, 1, 1) (v_z growing along y, v_x along z), so that each
// component of N x omega is exercised.
TEST(Vorticity, ConfinementPushesAlongTheRotationTowardStrongerVorticity) {
  const double a = 1.0, epsilon = 0.5, dt = 0.1;
  for (int along = 0; along < 3; ++along) {  // the flow varies along this axis...
    const int moving = (along + 1) % 3;      // ...and runs along this one
    const double b = a / (kN[along] * kS);
    Simulation sim;
    run_one_step(sim, dt, epsilon, [&](double x, double y, double z, double v[3]) {
      const double q = along == 0 ? x : along == 1 ? y : z;
      v[0] = v[1] = v[2] = 0;
      v[moving] = a * q + b * q * q / 2;
    });
    const auto& P = sim.particles();
    const real* position[3] = {P.x(), P.y(), P.z()};
    const real* velocity[3] = {P.vx(), P.vy(), P.vz()};
    const double kappa = test::gradient_norm(kS, sim.kernels());
    int bulk = 0;
    for (std::size_t i = 0; i < P.size(); ++i) {
      if (!test::in_bulk(kN, kS, 3 * kH, P.x()[i], P.y()[i], P.z()[i])) continue;
      ++bulk;
      const double q = position[along][i];
      const double omega = kappa * (a + b * q), expected = -dt * epsilon * kH * omega * omega;
      const double v0 = real(a * q + b * q * q / 2), dv = velocity[moving][i] - v0;
      // |omega| and omega each carry the curl's rounding (1.5 kSumRounding of it, see above;
      // N's direction errs only at second order), and v0 + dv was rounded to u |v0 + dv|.
      const double tolerance = 2 * 1.5 * kSumRounding * std::fabs(expected) +
                               2 * test::kUnitRoundoff * (std::fabs(v0) + std::fabs(expected));
      ASSERT_NEAR(dv, expected, tolerance) << "flow along axis " << moving << ", particle at " << q;
    }
    EXPECT_EQ(bulk, 4 * 4 * 4);
  }
}
