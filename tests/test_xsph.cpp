// XSPH smooths each velocity toward its neighbours' by the coefficient c asked for:
//   v_i += c sum_j V_j (v_j - v_i) W_ij,   V_j = m_j / rho_j.
// On a shear wave u_x = U sin(k z) set on the lattice (tests/bulk_lattice.hpp), at a bulk
// particle (2h deep: its neighbours' volumes need full neighbourhoods) every V_j is the bulk
// volume V, and u_j - u_i = -u_i (1 - cos k r_z) + U cos(k z_i) sin(k r_z), whose second part
// is odd in r_j and sums to zero against the even weights. So one application multiplies the
// wave by exactly
//   1 - c D,   D = V sum_j W(r_j) (1 - cos k r_z)
// (0.033 for a wavelength of 12 spacings at h = 2s), and leaves u_y and u_z zero. A coefficient
// applied twice, or not at all, misses by c D U, 33 times the rounding bound below.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "bulk_lattice.hpp"
#include "engine/core/simulation.hpp"
#include "engine/registry/style_registry.hpp"

using namespace pbf;

namespace {

constexpr int kN[3] = {12, 12, 12};
constexpr double kS = 0.01, kU = 0.1, kC = 0.1;
constexpr double kK = 2 * std::numbers::pi / (12 * kS);
constexpr double kReach = (kN[0] - 1) / 2.0;  // the largest |coordinate| of a site, in spacings

double wave(double z) { return kU * std::sin(kK * z); }

}  // namespace

TEST(Xsph, SmoothsAShearWaveByTheCoefficientAskedFor) {
  Simulation sim;
  test::centred_block(sim, kN, kS, 1e-4);
  const auto& styles = StyleRegistry::builtin();
  sim.add_fix(styles.make_fix("integrator", "leapfrog", {}));
  // The wave after the integrator's velocity update (the particles have not moved: they
  // started at rest), before XSPH's velocity_post.
  sim.add_fix(std::make_unique<test::SetVelocities>(Stage::velocity_update, [](double, double, double z, double v[3]) {
    v[0] = wave(z);
    v[1] = v[2] = 0;
  }));
  sim.add_fix(styles.make_fix("xsph", "xsph", {{"c", kC}}));
  sim.run(1);

  const Kernels& K = sim.kernels();
  const double V = test::bulk_volume(kS, K);
  const double D = V * test::lattice_sum(kS, K, [&](double, double, double rz, double r2) {
    return double(K.W(real(r2))) * (1 - std::cos(kK * rz));
  });
  ASSERT_GT(D, 0.02);
  ASSERT_LT(D, 0.05);
  // Rounding: the smoothing sum's, pair_sum_rounding of the sum of its terms' sizes (at most
  // 2U: the weights V W sum to 1 - V W(0) < 1), times c; then the stored velocity's half unit
  // in its last place.
  const double bound = kC * test::pair_sum_rounding(kReach) * 2 * kU + test::kUnitRoundoff * kU;
  const auto& P = sim.particles();
  int bulk = 0;
  for (std::size_t i = 0; i < P.size(); ++i) {
    if (!test::in_bulk(kN, kS, 2 * K.h, P.x()[i], P.y()[i], P.z()[i])) continue;
    ++bulk;
    const double expected = wave(P.z()[i]) * (1 - kC * D);
    ASSERT_NEAR(P.vx()[i], expected, bound) << "particle " << P.ids()[i] << " at z = " << P.z()[i];
    ASSERT_NEAR(P.vy()[i], 0, bound) << "particle " << P.ids()[i];
    ASSERT_NEAR(P.vz()[i], 0, bound) << "particle " << P.ids()[i];
  }
  EXPECT_EQ(bulk, 6 * 6 * 6);  // the sites within 2.5 s of the centre: 4 s (2h) from the first missing ones
}
