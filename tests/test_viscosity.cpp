// The WCSPH viscosities on a shear wave u_x = U sin(k z): its amplitude must start to decay
// at du/dt = -nu_eff k^2 u, with nu_eff the effective viscosity of each form on the
// lattice, derived below from the form's pair sum. The wave is set as the velocities in the
// forces stage, before sph_viscosity (tests/bulk_lattice.hpp): the particles sit exactly on
// the lattice, and the acceleration field after the step is the viscosity's. No pressure, no
// gravity, no walls.
//
// On the lattice at a bulk particle (2h deep: the neighbours' densities need full
// neighbourhoods), with r_j = x_j - x_i, gradW_ij = -g(r_j) r_j and V = m / rho, both forms
// are sums of w_j (u_i - u_j), and
//   u_i - u_j = u_i (1 - cos k r_z) - U cos(k z_i) sin(k r_z),
// whose second part is odd in r_j and sums to zero against weights even in r_j. So
// a_x,i = -nu_eff k^2 u_i exactly, with
//   Laplacian:  -nu_eff k^2 = 2 nu / kappa V sum_j g r^2 / (r^2 + eta^2) (1 - cos k r_z),
//               kappa = -V sum_j g r^2 r_z^2 / (r^2 + eta^2)   (sph_viscosity's lattice factor)
//   artificial: -nu_eff k^2 = alpha c0 h V / 2 sum_j g r_x^2 / (r^2 + eta^2) (1 - cos k r_z)
// (eta^2 = 0.01 h^2). The artificial form acts only between approaching particles,
// v_ij . x_ij = (u_i - u_j) r_x < 0: of the mirror pair r_j, (-r_x, r_y, r_z), which share
// u_i - u_j and the weight, exactly one approaches, so the switch halves the sum exactly.
// At long waves (1 - cos k r_z -> k^2 r_z^2 / 2) the Laplacian's tends to nu on any lattice:
// the division by kappa makes it so (kappa = 0.922 at h = 2s: the lattice sum, and the
// regularisation, which keeps even the continuum's at 0.958). At a wavelength of 12 spacings
// it is 0.977 nu (0.90 nu undivided), at 16 0.987 nu, at 48 0.9986 nu. A quadratic field,
// u = U z^2 / L^2, gets exactly nu u'' = 2 nu U / L^2 (the second test). The artificial form
// tends to Monaghan's alpha c0 h / (2 (d + 2)) = alpha c0 h / 10 halved by the switch,
// alpha c0 h / 20, with h the engine's support radius (the sum of g r_x^2 r_z^2 / r^2 is
// -kappa_g / 5 for an isotropic kernel, kappa_g = -1/3 V sum g r^2): the lattice gives
// 0.55 alpha c0 h / 20 at h = 2s and a wavelength of 12 spacings, the 26-neighbour cube's
// fourth moment being 0.57 of an isotropic one's (0.98 at h = 4s). A viscosity halved halves
// the decay.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "bulk_lattice.hpp"
#include "engine/core/simulation.hpp"
#include "engine/registry/style_registry.hpp"

using namespace pbf;

namespace {

constexpr int kN[3] = {12, 12, 12};
constexpr double kS = 0.01, kH = 2 * kS, kU = 0.1;
constexpr double kK = 2 * std::numbers::pi / (12 * kS);  // a wavelength of 12 spacings
constexpr double kReach = (kN[0] - 1) / 2.0;          // the largest |coordinate| of a site, in spacings

double wave(double z) { return kU * std::sin(kK * z); }

// One step of the block with the wave set before `params`' sph_viscosity.
void run_shear_wave(Simulation& sim, const GivenParams& params) {
  test::centred_block(sim, kN, kS, 1e-4);
  const auto& styles = StyleRegistry::builtin();
  sim.add_fix(styles.make_fix("integrator", "leapfrog", {}));
  sim.add_fix(std::make_unique<test::SetVelocities>(Stage::forces, [](double, double, double z, double v[3]) {
    v[0] = wave(z);
    v[1] = v[2] = 0;
  }));
  sim.add_fix(styles.make_fix("viscosity", "sph_viscosity", params));
  sim.run(1);
}

// a_x at every bulk particle is rate u_x, rate = sum_j weight(r_j) (1 - cos k r_z), to the
// rounding of that sum: pair_sum_rounding of the terms' sizes, the weights times
// |u_i - u_j| <= U (1 - cos k r_z + |sin k r_z|), plus the stored velocities' own error,
// 2 u U per term.
template <class Weight>
void expect_decay_rate(const Simulation& sim, Weight weight) {
  const Kernels& K = sim.kernels();
  auto sum = [&](auto term) {
    return test::lattice_sum(kS, K, [&](double rx, double ry, double rz, double r2) {
      return term(weight(rx, ry, rz, r2), kK * rz);
    });
  };
  const double rate = sum([](double w, double kr) { return w * (1 - std::cos(kr)); });
  const double sizes = sum([](double w, double kr) { return std::fabs(w) * kU * (1 - std::cos(kr) + std::fabs(std::sin(kr))); });
  const double weights = sum([](double w, double) { return std::fabs(w); });
  const double tolerance = test::pair_sum_rounding(kReach) * sizes + 2 * test::kUnitRoundoff * kU * weights;
  const auto& P = sim.particles();
  const auto field = P.find("acceleration");
  int bulk = 0;
  for (std::size_t i = 0; i < P.size(); ++i) {
    if (!test::in_bulk(kN, kS, 2 * kH, P.x()[i], P.y()[i], P.z()[i])) continue;
    ++bulk;
    // The wave as it was set (the leapfrog's kick has since changed the velocity by dt a).
    const double u = real(wave(P.z()[i]));
    EXPECT_NEAR(P.data(*field, 0)[i], rate * u, tolerance) << "particle at z = " << P.z()[i];
  }
  EXPECT_EQ(bulk, 6 * 6 * 6);
}

}  // namespace

TEST(Viscosity, LaplacianFormDecaysAShearWaveAtItsViscosity) {
  const double nu = 1e-3;
  Simulation sim;
  run_shear_wave(sim, {{"kind", std::string("laplacian")}, {"nu", nu}});
  const Kernels& K = sim.kernels();
  const double V = test::bulk_volume(kS, K), eta2 = 0.01 * kH * kH, kappa = test::laplacian_factor(kS, K);
  expect_decay_rate(sim, [&](double, double, double, double r2) {
    return 2 * nu / kappa * V * K.grad_factor(real(r2)) * r2 / (r2 + eta2);
  });
  const double nu_eff = test::lattice_sum(kS, K, [&](double, double, double rz, double r2) {
    return -2 * nu / kappa * V * K.grad_factor(real(r2)) * r2 / (r2 + eta2) * (1 - std::cos(kK * rz)) / (kK * kK);
  });
  RecordProperty("kappa", fmt::format("{:.4f}", kappa));
  RecordProperty("nu_eff_over_nu", fmt::format("{:.4f}", nu_eff / nu));
}

// u_x = U z^2 / L^2: at every bulk particle a_x = nu u'' = 2 nu U / L^2, the Laplacian's
// exact value (the sum's lattice factor divided out), to the rounding of the sum: the terms'
// sizes, weight |u_j - u_i| <= weight U (2 |z_i| |r_z| + r_z^2) / L^2, and the stored
// velocities' error, 2 u max |u| per term's weight (max |u| = U (|z_i| + h)^2 / L^2 over the
// neighbours).
TEST(Viscosity, LaplacianFormGivesAQuadraticFieldItsExactLaplacian) {
  const double nu = 1e-3, L = 6 * kS;
  Simulation sim;
  test::centred_block(sim, kN, kS, 1e-4);
  const auto& styles = StyleRegistry::builtin();
  sim.add_fix(styles.make_fix("integrator", "leapfrog", {}));
  sim.add_fix(std::make_unique<test::SetVelocities>(Stage::forces, [&](double, double, double z, double v[3]) {
    v[0] = kU * z * z / (L * L);
    v[1] = v[2] = 0;
  }));
  sim.add_fix(styles.make_fix("viscosity", "sph_viscosity", {{"kind", std::string("laplacian")}, {"nu", nu}}));
  sim.run(1);
  const Kernels& K = sim.kernels();
  const double V = test::bulk_volume(kS, K), eta2 = 0.01 * kH * kH, kappa = test::laplacian_factor(kS, K);
  auto weight = [&](double r2) { return -2 * nu / kappa * V * K.grad_factor(real(r2)) * r2 / (r2 + eta2); };
  const double expected = 2 * nu * kU / (L * L);
  const auto& P = sim.particles();
  const auto field = P.find("acceleration");
  int bulk = 0;
  for (std::size_t i = 0; i < P.size(); ++i) {
    if (!test::in_bulk(kN, kS, 2 * kH, P.x()[i], P.y()[i], P.z()[i])) continue;
    ++bulk;
    const double z = P.z()[i];
    const double sizes = test::lattice_sum(kS, K, [&](double, double, double rz, double r2) {
      return weight(r2) * kU * (2 * std::fabs(z) * std::fabs(rz) + rz * rz) / (L * L);
    });
    const double weights = test::lattice_sum(kS, K, [&](double, double, double, double r2) { return weight(r2); });
    const double largest = kU * (std::fabs(z) + kH) * (std::fabs(z) + kH) / (L * L);  // |u| over the neighbours
    const double tolerance = test::pair_sum_rounding(kReach) * sizes + 2 * test::kUnitRoundoff * largest * weights;
    EXPECT_NEAR(P.data(*field, 0)[i], expected, tolerance) << "particle at z = " << z;
  }
  EXPECT_EQ(bulk, 6 * 6 * 6);
}

TEST(Viscosity, ArtificialFormDecaysAShearWaveAtMonaghansViscosity) {
  const double alpha = 0.1, c0 = 10;
  Simulation sim;
  run_shear_wave(sim, {{"kind", std::string("artificial")}, {"alpha", alpha}, {"sound_speed", c0}});
  const Kernels& K = sim.kernels();
  const double V = test::bulk_volume(kS, K), eta2 = 0.01 * kH * kH;
  expect_decay_rate(sim, [&](double rx, double, double, double r2) {
    return alpha * c0 * kH * V / 2 * K.grad_factor(real(r2)) * rx * rx / (r2 + eta2);
  });
}
