// PBF's Jacobi iteration on a density mode, against its linearisation (engine/fixes/pbf.cpp,
// docs/physics.md "The Jacobi iteration overshoots at the paper's relaxation"): one iteration
// multiplies a mode of wave vector k by 1 - omega a(k) / (1 + epsilon).
//
// (A uniformly compressed block would not do: in the bulk every particle's correction
// sum_j (lambda_i + lambda_j) gradW_ij vanishes by symmetry, a(0) = 0; only its surface moves.)
//
// The mode: lattice sites displaced along x by xi_i = A sin(k x_i). With r_j = x_j - x_i,
// gradW_ij = -g(r_j) r_j, V = m / rho0, and to first order in A, at a bulk particle
//   C_i      = V sum_j g r_x (xi_j - xi_i) = A cos(k x_i) G,      G = V sum_j g r_x sin(k r_x)
//   lambda_i = -omega C_i / (S0 (1 + epsilon)),  S0 = V^2 sum_j g^2 r^2 (the bulk's sum_k |grad_k C_i|^2)
//   dx_i     = V sum_j (lambda_i + lambda_j) gradW_ij = -omega a / (1 + epsilon) xi_i,  a = G^2 / S0
// (the parts even in r_j sum to zero). So the displacement, and the compression C with it,
// shrinks by F = 1 - omega a / (1 + epsilon) per iteration. The second-order terms are modes
// 0 and 2k, which the projection onto sin(k x) over whole wavelengths removes. A denominator
// doubled or 1.3 times too large gives 1 - omega a / (2 or 1.3 (1 + epsilon)).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "bulk_lattice.hpp"
#include "engine/core/simulation.hpp"
#include "engine/registry/style_registry.hpp"

using namespace pbf;

TEST(PbfConvergence, OneIterationShrinksADensityModeByTheLinearisedFactor) {
  // 22 x 8 x 8 sites: the bulk (2h deep: a correction reads the neighbours' lambda, which
  // read theirs) is 16 x 2 x 2 sites, two whole wavelengths of 8 spacings along x.
  const int n[3] = {22, 8, 8};
  const double s = 0.01, k = 2 * std::numbers::pi / (8 * s), A = 0.004 * s;
  const double omega = 0.7, epsilon = 0.01;  // the defaults
  Simulation sim;
  test::centred_block(sim, n, s, 1e-3);
  auto& P = sim.particles();
  std::vector<std::array<double, 3>> site(P.size());  // each particle's site, by id
  const auto index = P.index_of_id();
  for (std::size_t id = 0; id < P.size(); ++id) {
    const std::size_t i = index[id];
    site[id] = {P.x()[i], P.y()[i], P.z()[i]};
    P.x()[i] = real(site[id][0] + A * std::sin(k * site[id][0]));
  }
  sim.positions_changed();
  sim.add_fix(StyleRegistry::builtin().make_fix(
      "pbf", "pbf",
      {{"iterations", std::int64_t{1}}, {"one_sided", false}, {"relaxation", omega}, {"epsilon", epsilon}}));
  sim.run(1);  // at rest: the prediction moves nothing, one iteration, velocities from it

  const Kernels& K = sim.kernels();
  const double V = test::bulk_volume(s, K);
  const double G = V * test::lattice_sum(s, K, [&](double rx, double, double, double r2) {
    return K.grad_factor(real(r2)) * rx * std::sin(k * rx);
  });
  const double S0 = V * V * test::lattice_sum(s, K, [&](double, double, double, double r2) {
    return double(K.grad_factor(real(r2))) * K.grad_factor(real(r2)) * r2;
  });
  const double correction = omega * G * G / S0 / (1 + epsilon), expected = 1 - correction;

  // The displacement's projection on sin(k x) over the bulk, after and before.
  double after = 0, before = 0;
  int bulk = 0;
  const auto now = P.index_of_id();
  for (std::size_t id = 0; id < P.size(); ++id) {
    const std::size_t i = now[id];
    const double x = site[id][0];
    if (!test::in_bulk(n, s, 4 * s, x, site[id][1], site[id][2])) continue;
    ++bulk;
    after += (P.x()[i] - x) * std::sin(k * x);
    before += A * std::sin(k * x) * std::sin(k * x);
  }
  ASSERT_EQ(bulk, 16 * 2 * 2);
  // Bound on the measured factor after / before:
  //  - third order in A, in the mode k: each Taylor term of W or g in the displacement
  //    difference d <= A k |r_x| <= A k h is at most |W'''| d^2 / (6 |W'|) <= 283 / 6 (A k)^2
  //    of the linear one (f''/f for f = q (1 - q)^3 at the farthest neighbour, q = sqrt(3)/2),
  //    and the linear sums do not cancel (every term of G has g r_x sin(k r_x) <= 0); three
  //    such sums (C, the denominator, the correction): 150 (A k)^2 of the correction.
  //  - rounding: C errs by pair_sum_rounding (sum_j V W = 1) against its amplitude A |G|, and
  //    the correction's sums by pair_sum_rounding of themselves; the positions, stored to
  //    u L (L = 10.5 s), perturb the measured displacement by u L / A before and after.
  const double reach = (n[0] - 1) / 2.0, rounding = test::pair_sum_rounding(reach);
  const double tolerance = (150 * (A * k) * (A * k) + rounding * (1 / (A * std::fabs(G)) + 2)) * correction +
                           2 * test::kUnitRoundoff * reach * s / A;
  EXPECT_NEAR(after / before, expected, tolerance) << "a(k) = " << correction * (1 + epsilon) / omega;
}
