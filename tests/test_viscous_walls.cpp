// The Laplacian viscosity's no-slip wall term (engine/sph/viscous_wall.hpp): one force
// evaluation on a set velocity field, as the shear-wave test of test_viscosity.cpp, in a slab
// of lattice particles whose lowest layer sits half a spacing above the floor z = 0.
//
// On the lattice (h = 2s, V = 1 / sum W the bulk volume), with the field's u_j - u_i at the
// sites r_j = x_j - x_i, Morris's sum at a particle whose neighbours are all at rest density is
//   a_x = 2 nu' V sum_j (-g(r_j)) r_j^2 / (r_j^2 + eta^2) (u_j - u_i)   (gradW = g r_vec),
// over the sites present, nu' = nu / kappa with kappa = V sum_j (-g) r^2 / (r^2 + eta^2) r_z^2
// the sum's lattice factor (0.922 at h = 2s), which sph_viscosity divides out. The wall adds
// nu' (1 + rho0/rho_i) Psi(d) (u_w - u_i), which for the
// first layer (d = s/2) equals what the lattice sites behind the wall would give were their
// velocities the linear continuation u_j = u_w + (u_i - u_w) z_j / d (the wall's delta_v is
// chosen so). Hence:
//  - a linear shear u = U z / H: the first layer gets exactly the full lattice's sum, zero;
//    the second layer (d = 3s/2) sees no lattice site behind the wall (all lie at h or beyond)
//    but a sliver of the wall's continuum (within h - delta_v): 2 nu' Psi(3s/2) (0 - u_i);
//  - a parabola u = U z (H - z) between floor and ceiling: the bulk gets nu' kappa u'' =
//    nu u'' = -2 U nu, the exact Laplacian's; the first layer misses the curvature behind the
//    wall, which the linear continuation lacks: -2 U nu (1 - eps_1), with
//    eps_1 nu = nu' V sum_{behind} (-g) r^2 / (r^2 + eta^2) z_j (z_j - d) (0.25 at h = 2s);
//  - a plate moving at U_w under fluid at rest: the first layer gets
//    nu' (1 + rho0 / rho_i) Psi(s/2) U_w = nu' (1 + rho0 / rho_i) U_w 2 B / s, B the lattice
//    sites' sum behind the wall, V sum (-g) r^2 / (r^2 + eta^2) |r_z|.
// Tolerances: the rounding of the pair sums (tests/bulk_lattice.hpp) and the neighbours'
// densities, which differ from rho0 near the wall (the wall density's continuum against the
// lattice): a term weighted 1/rho_j errs by |rho0/rho_j - 1|, read from the run, times the
// terms' sizes.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "bulk_lattice.hpp"
#include "engine/core/simulation.hpp"
#include "engine/geometry/motion.hpp"
#include "engine/registry/style_registry.hpp"
#include "engine/sph/viscous_wall.hpp"
#include "engine/sph/wall_density.hpp"

using namespace pbf;

namespace {

constexpr double kS = 0.01, kH = 2 * kS, kNu = 1e-3;
constexpr int kNx = 12, kNz = 12;  // the slab: kNx x kNx sites across, kNz layers
constexpr double kTop = kNz * kS;  // the ceiling, when there is one

using Field = test::SetVelocities::Field;

using Walls = std::vector<std::pair<std::string, GivenParams>>;

// The slab above z = 0 (the domain's floor, or with `floor_below` a floor a spacing lower
// for a solid to stand on), up to a ceiling at kTop with `ceiling`; side walls 3h beyond it;
// the field set in the forces stage before the Laplacian viscosity; one step. `walls`: the
// fixes that hold the fluid (style, params), each with its style as id.
void run_slab(Simulation& sim, const Field& field, bool ceiling, const Walls& walls, bool floor_below = false) {
  const double side = kNx * kS / 2 + 3 * kH;
  sim.set_domain(Domain{{-side, -side, floor_below ? -3 * kH : 0.0}, {side, side, ceiling ? kTop : 1.0}});
  sim.set_kernel_radius(kH);
  sim.set_timestep(1e-4);
  const double lo[3] = {-kNx * kS / 2, -kNx * kS / 2, 0}, hi[3] = {kNx * kS / 2, kNx * kS / 2, kTop}, rest[3] = {0, 0, 0};
  add_lattice(sim, lo, hi, kS, rest);
  const auto& styles = StyleRegistry::builtin();
  sim.add_fix(styles.make_fix("integrator", "leapfrog", {}));
  sim.add_fix(std::make_unique<test::SetVelocities>(Stage::forces, field));
  sim.add_fix(styles.make_fix("viscosity", "sph_viscosity", {{"kind", std::string("laplacian")}, {"nu", kNu}}));
  for (const auto& [style, params] : walls) sim.add_fix(styles.make_fix(style, style, params));
  sim.run(1);
}

GivenParams box(bool no_slip) { return {{"no_slip", no_slip}}; }

// Away from the slab's sides by 2h: the particle's sum and its neighbours' see the walls only.
bool mid_slab(double x, double y) {
  return (kNx + 1) * kS / 2 - std::max(std::fabs(x), std::fabs(y)) >= 2 * kH - 1e-6 * kS;
}

// The layer a particle is in, 1 at the floor.
int layer(double z) { return static_cast<int>(std::lround(z / kS + 0.5)); }

// The coefficient of sph_viscosity's sum, nu' = nu / kappa.
double nu_sum(const Kernels& K) { return kNu / test::laplacian_factor(kS, K); }

// Morris's pair weight on the lattice, 2 nu' V (-g) r^2 / (r^2 + eta^2).
double weight(const Kernels& K, double r2) {
  return -2 * nu_sum(K) * test::bulk_volume(kS, K) * K.grad_factor(real(r2)) * r2 / (r2 + 0.01 * kH * kH);
}

// The largest |rho0 / rho - 1| (the density the viscosity used: the summed one) over the
// neighbours of the mid-slab particles: those at least h from the slab's missing sites at the
// sides and, without a ceiling, at the top (their own sums see the walls only).
double density_deviation(Simulation& sim, bool ceiling) {
  const auto& rho = sim.summed_density();
  const auto& P = sim.particles();
  double worst = 0;
  for (std::size_t i = 0; i < P.size(); ++i) {
    const double side = (kNx + 1) * kS / 2 - std::max(std::fabs(P.x()[i]), std::fabs(P.y()[i]));
    if (side < kH - 1e-6 * kS || (!ceiling && kTop + kS / 2 - P.z()[i] < kH - 1e-6 * kS)) continue;
    worst = std::max(worst, std::fabs(sim.rest_density() / rho[i] - 1));
  }
  return worst;
}

struct Layers {
  std::vector<double> a;  // a_x of the mid-slab particles of each layer, 1..kNz (index 0 unused)
  std::vector<int> count;
};

// a_x by layer, checking that every mid-slab particle of a layer has the same (to `tol`).
Layers accelerations(const Simulation& sim) {
  const auto& P = sim.particles();
  const real* ax = P.data(*P.find("acceleration"), 0);
  Layers out{std::vector<double>(kNz + 1, 0), std::vector<int>(kNz + 1, 0)};
  for (std::size_t i = 0; i < P.size(); ++i) {
    if (!mid_slab(P.x()[i], P.y()[i])) continue;
    const int k = layer(P.z()[i]);
    out.a[k] += ax[i];
    ++out.count[k];
  }
  for (int k = 1; k <= kNz; ++k) out.a[k] /= std::max(out.count[k], 1);
  return out;
}

}  // namespace

// A linear shear above a no-slip floor at rest: zero acceleration at the wall layers, as in
// the bulk, with the wall term; without it, the first layer misses its slow side.
TEST(ViscousWall, ALinearShearAboveANoSlipFloorFeelsNoForce) {
  const double U = 0.1;
  const Field shear = [&](double, double, double z, double v[3]) { v[0] = U * z / kTop, v[1] = v[2] = 0; };
  Simulation with, without;
  run_slab(with, shear, false, {{"box", box(true)}});
  run_slab(without, shear, false, {{"box", box(false)}});
  const Kernels& K = with.kernels();
  // The terms' sizes, weight |u_j - u_i| = weight U |r_z| / H, and the first layer's
  // missing share (the lattice sites behind the floor), which the wall term supplies.
  const double sizes = test::lattice_sum(kS, K, [&](double, double, double rz, double r2) {
    return weight(K, r2) * U * std::fabs(rz) / kTop;
  });
  const double missing = test::lattice_sum(kS, K, [&](double, double, double rz, double r2) {
    return rz < -kS / 2 ? weight(K, r2) * U * -rz / kTop : 0.0;
  });
  const double tolerance = (test::pair_sum_rounding(kNx / 2.0) + density_deviation(with, false)) * sizes;
  // The second layer: the wall's continuum within h - delta_v of it, 2 nu' Psi(3s/2) (0 - u).
  NoSlipWall wall;
  wall.prepare(with);
  const double second = -2 * nu_sum(K) * double(wall.share(real(1.5 * kS))) * U * 1.5 * kS / kTop;
  const Layers a = accelerations(with), a0 = accelerations(without);
  ASSERT_EQ(a.count[1], 36);  // the 6 x 6 mid-slab sites of a layer
  EXPECT_NEAR(a.a[1], 0, tolerance) << "the first layer, without the term: " << a0.a[1];
  EXPECT_NEAR(a.a[2], second, tolerance) << "the second layer";
  EXPECT_NEAR(a.a[3], 0, tolerance) << "the third layer";
  // Without the term the first layer gets the missing share (the test sees the difference).
  EXPECT_NEAR(a0.a[1], missing, tolerance);
  EXPECT_GT(std::fabs(a0.a[1]), 20 * tolerance);
  RecordProperty("layers_1_2_3", fmt::format("{:.3g} {:.3g} {:.3g}", a.a[1], a.a[2], a.a[3]));
  RecordProperty("second_expected", fmt::format("{:.3g}", second));
  RecordProperty("without_1_2", fmt::format("{:.3g} {:.3g}", a0.a[1], a0.a[2]));
  RecordProperty("tolerance", fmt::format("{:.3g}", tolerance));
}

// A parabola between a no-slip floor and ceiling: nu u'' = -2 U nu at every layer, but the
// first (1 - eps_1: the curvature behind the wall) and the second (the wall continuum's sliver).
TEST(ViscousWall, AParabolaBetweenNoSlipPlatesHasItsLaplacianAtEveryLayer) {
  const double U = 0.1 / (kTop * kTop / 4);  // 0.1 m/s midway
  auto u = [&](double z) { return U * z * (kTop - z); };
  const Field parabola = [&](double, double, double z, double v[3]) { v[0] = u(z), v[1] = v[2] = 0; };
  Simulation with, without;
  run_slab(with, parabola, true, {{"box", box(true)}});
  run_slab(without, parabola, true, {{"box", box(false)}});
  const Kernels& K = with.kernels();
  // The bulk's -2 U nu, eps_1 nu (the sites behind the floor, z_j = d + r_z < 0 for the
  // first layer at d = s/2), and the terms' sizes, weight times |u_j - u_i| <= |u'| |r_z| +
  // U r_z^2 with |u'| <= U H.
  const double d1 = kS / 2;
  const double eps_nu = test::lattice_sum(kS, K, [&](double, double, double rz, double r2) {
    return rz < -d1 ? weight(K, r2) * (d1 + rz) * rz / 2 : 0.0;
  });
  const double sizes = test::lattice_sum(kS, K, [&](double, double, double rz, double r2) {
    return weight(K, r2) * (U * kTop * std::fabs(rz) + U * rz * rz);
  });
  const double tolerance = (test::pair_sum_rounding(kNx / 2.0) + density_deviation(with, true)) * sizes;
  NoSlipWall wall;
  wall.prepare(with);
  const double d2 = 1.5 * kS, sliver = -2 * nu_sum(K) * double(wall.share(real(d2))) * u(d2);
  const Layers a = accelerations(with), a0 = accelerations(without);
  for (int k = 1; k <= kNz; ++k) {
    const int from_wall = std::min(k, kNz + 1 - k);
    const double expected = -2 * U * kNu + (from_wall == 1 ? 2 * U * eps_nu : 0) + (from_wall == 2 ? sliver : 0);
    EXPECT_NEAR(a.a[k], expected, tolerance) << "layer " << k << " (bulk: " << -2 * U * kNu << ")";
  }
  // Without the term the wall layers miss their slow side by far more than the tolerance.
  EXPECT_GT(a0.a[1] - a.a[1], 20 * tolerance);
  RecordProperty("eps_1", fmt::format("{:.4f}", eps_nu / kNu));
  RecordProperty("kappa", fmt::format("{:.4f}", kNu / nu_sum(K)));
  RecordProperty("layers_1_2_3_over_bulk", fmt::format("{:.4f} {:.4f} {:.4f}", a.a[1] / (-2 * U * kNu),
                                                       a.a[2] / (-2 * U * kNu), a.a[3] / (-2 * U * kNu)));
  RecordProperty("without_1_2_over_bulk", fmt::format("{:.3f} {:.3f}", a0.a[1] / (-2 * U * kNu), a0.a[2] / (-2 * U * kNu)));
  RecordProperty("tolerance_over_bulk", fmt::format("{:.3g}", tolerance / (2 * U * kNu)));
}

// A plate sliding along x at U_w under fluid at rest (a solid with a keyframed motion): the
// first layer is dragged along at nu' (1 + rho0 / rho_i) U_w 2 B / s; the third feels nothing.
TEST(ViscousWall, AMovingPlateDragsTheFirstLayer) {
  const double Uw = 0.1;
  std::vector<Keyframes::Key> keys = {{0, Pose{{0, 0, 0}, {0, 0, 0}}}, {1, Pose{{Uw, 0, 0}, {0, 0, 0}}}};
  const GivenParams plate = {{"shape", std::string("box")}, {"lo", Vec3{-0.2, -0.2, -0.05}}, {"hi", Vec3{0.2, 0.2, 0}},
                             {"no_slip", true},
                             {"motion", std::make_shared<Keyframes>(keys, Keyframes::Interpolation::linear, "test")}};
  const Field rest = [](double, double, double, double v[3]) { v[0] = v[1] = v[2] = 0; };
  Simulation sim;
  run_slab(sim, rest, false, {{"solid", plate}}, true);
  const Kernels& K = sim.kernels();
  const double B = test::lattice_sum(kS, K, [&](double, double, double rz, double r2) {
    return rz < -kS / 2 ? weight(K, r2) / (2 * nu_sum(K)) * -rz : 0.0;
  });
  // rho_i is the run's. The solid moved the first layer out to its contact distance and a
  // hair (1e-3 of its map's cell, h/4) before the run, and the map's d_eff on a flat wall
  // gives the wall's fraction f to 0.002 (tests/test_solid.cpp), d_eff to 0.002 / |f'(d)|
  // (f' of engine/sph/wall_density.hpp): Psi changes by its logarithmic slope
  // (|dln Psi/dd| < 10 / h at d = s/2: 4/h from 1/d, 5.3/h from b) times these.
  HalfSpaceWall plane;
  plane.prepare(sim);
  const double hair = 1e-3 * kH / 4;
  real slope;
  plane.fraction(real(kS / 2 + hair), slope);
  const double relative = 10 / kH * (hair + 0.002 / std::fabs(double(slope))) + test::pair_sum_rounding(kNx / 2.0);
  const auto& P = sim.particles();
  const real* ax = P.data(*P.find("acceleration"), 0);
  const auto& rho = sim.summed_density();
  int first = 0;
  for (std::size_t i = 0; i < P.size(); ++i) {
    if (!mid_slab(P.x()[i], P.y()[i])) continue;
    if (layer(P.z()[i]) == 1) {
      ++first;
      const double expected = nu_sum(K) * (1 + sim.rest_density() / rho[i]) * Uw * 2 * B / kS;
      EXPECT_NEAR(ax[i], expected, relative * expected);
    }
    if (layer(P.z()[i]) == 3) EXPECT_EQ(ax[i], 0);
  }
  EXPECT_EQ(first, 36);
}

// The same bits at 1 and 2 threads, for the box's floor and ceiling and a moving plate.
TEST(ViscousWall, SameBitsAtOneAndTwoThreads) {
  const double U = 0.1;
  const Field shear = [&](double x, double y, double z, double v[3]) {
    v[0] = U * z * (kTop - z) / (kTop * kTop), v[1] = U * std::sin(40 * x) * z / kTop, v[2] = 0.01 * U * y;
  };
  std::vector<Keyframes::Key> keys = {{0, Pose{{0, 0, 0}, {0, 0, 0}}}, {1, Pose{{U, U, 0}, {0, 0, 0}}}};
  const GivenParams plate = {{"shape", std::string("box")}, {"lo", Vec3{-0.2, -0.2, -0.05}}, {"hi", Vec3{0.2, 0.2, 0}},
                             {"no_slip", true},
                             {"motion", std::make_shared<Keyframes>(keys, Keyframes::Interpolation::linear, "test")}};
  for (bool solid : {false, true}) {
    std::vector<std::vector<real>> a;
    for (int threads : {1, 2}) {
      omp_set_num_threads(threads);
      Simulation sim;
      if (solid)
        run_slab(sim, shear, false, {{"solid", plate}}, true);
      else
        run_slab(sim, shear, true, {{"box", box(true)}});
      const auto& P = sim.particles();
      std::vector<real> by_id(3 * P.size());
      for (int c = 0; c < 3; ++c)
        for (std::size_t i = 0; i < P.size(); ++i)
          by_id[3 * static_cast<std::size_t>(P.ids()[i]) + c] = P.data(*P.find("acceleration"), c)[i];
      a.push_back(by_id);
    }
    omp_set_num_threads(1);
    EXPECT_TRUE(a[0] == a[1]) << (solid ? "moving plate" : "box");
  }
}

// Without a Laplacian viscosity a no-slip box holds the fluid by its touching particles (the
// first layer, at the contact distance): they lose their velocity along the wall after the
// velocity update; with one, the wall term holds it, and they keep theirs but for its pull.
TEST(ViscousWall, ANoSlipBoxStopsTouchingParticlesOnlyWithoutALaplacianViscosity) {
  const double U = 0.1;
  for (const bool viscous : {false, true}) {
    Simulation sim;
    const double side = kNx * kS / 2 + 3 * kH;
    sim.set_domain(Domain{{-side, -side, 0}, {side, side, 1}});
    sim.set_kernel_radius(kH);
    sim.set_timestep(1e-4);
    // The first layer a hair below the contact distance: the projection puts it there
    // exactly, touching in either precision (a lattice's s/2 may round either side of it).
    const double lo[3] = {-kNx * kS / 2, -kNx * kS / 2, 0}, hi[3] = {kNx * kS / 2, kNx * kS / 2, kTop}, v[3] = {U, 0, 0};
    add_lattice(sim, lo, hi, kS, v);
    auto& Q = sim.particles();
    for (std::size_t i = 0; i < Q.size(); ++i) Q.z()[i] = real(Q.z()[i] - 1e-4 * kS);
    const auto& styles = StyleRegistry::builtin();
    sim.add_fix(styles.make_fix("integrator", "leapfrog", {}));
    if (viscous)
      sim.add_fix(styles.make_fix("viscosity", "sph_viscosity", {{"kind", std::string("laplacian")}, {"nu", kNu}}));
    sim.add_fix(styles.make_fix("walls", "box", box(true)));
    sim.run(1);
    const auto& P = sim.particles();
    for (std::size_t i = 0; i < P.size(); ++i) {
      if (!mid_slab(P.x()[i], P.y()[i]) || layer(P.z()[i]) > 2) continue;
      // With the term, the first layer loses dt nu' (1 + rho0/rho) Psi U, well below U / 10.
      if (layer(P.z()[i]) == 1 && !viscous)
        EXPECT_EQ(P.vx()[i], 0) << "a touching particle";
      else
        EXPECT_GT(P.vx()[i], 0.9 * U) << (viscous ? "the wall term holds the layer, " : "") << "layer " << layer(P.z()[i]);
    }
  }
}
