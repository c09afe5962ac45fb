// Moving solids: keyframes interpolate as stated (linear, or a spline through the keys whose
// velocity does not jump); the fluid in a container moving at constant speed behaves as in a
// container at rest (Galilean invariance, all three solvers); a wall moving into the fluid leaves
// no particle moving into it relative to the wall (all three solvers); a spinning no-slip cube drags
// the fluid touching it at its surface speed; time-step control keeps a fast
// wall's step below a fraction of h; a run with a moving solid continues bit for bit from a
// restart; bad motions are refused with a message that names them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "engine/core/error.hpp"
#include "engine/core/simulation.hpp"
#include "engine/geometry/motion.hpp"
#include "engine/registry/style_registry.hpp"
#include "engine/sph/lattice.hpp"
#include "test_util.hpp"

using namespace pbf;
using namespace pbf::test;

namespace {

std::unique_ptr<Fix> fix(const std::string& id, const std::string& style, const GivenParams& p = {}) {
  return StyleRegistry::builtin().make_fix(id, style, p);
}

// A translation along x through the keys (t, x).
MotionPtr along_x(std::vector<std::pair<double, double>> keys, Keyframes::Interpolation how) {
  std::vector<Keyframes::Key> k;
  for (auto [t, x] : keys) k.push_back({t, Pose{{x, 0, 0}, {0, 0, 0}}});
  return std::make_shared<Keyframes>(k, how, "test");
}

void add_solver(Simulation& sim, const std::string& solver) {
  if (solver == "pbf") {
    sim.add_fix(fix("pbf", "pbf"));
  } else if (solver == "dfsph") {  // as share/lua/solvers.lua assembles it
    sim.add_fix(fix("dfsph", "dfsph"));
    sim.add_fix(fix("viscosity", "sph_viscosity", {{"kind", std::string("laplacian")}, {"nu", 1e-3}}));
    sim.add_fix(fix("cfl", "cfl", {{"courant", 0.4}}));
  } else {
    sim.add_fix(fix("integrator", "leapfrog"));
    sim.add_fix(fix("wcsph", "wcsph"));
    sim.add_fix(fix("viscosity", "sph_viscosity"));
  }
}

}  // namespace

TEST(Keyframes, InterpolateLinearlyOrOnASplineAndHoldBeyondTheKeys) {
  const auto linear = along_x({{0, 0}, {1, 1}, {2, 0}}, Keyframes::Interpolation::linear);
  EXPECT_DOUBLE_EQ(linear->at(0.25).translate[0], 0.25);
  EXPECT_DOUBLE_EQ(linear->at(1.5).translate[0], 0.5);
  EXPECT_DOUBLE_EQ(linear->at(-1).translate[0], 0);
  EXPECT_DOUBLE_EQ(linear->at(5).translate[0], 0);
  const auto spline = along_x({{0, 0}, {1, 1}, {3, 2}, {4, 0}}, Keyframes::Interpolation::spline);
  for (auto [t, x] : std::vector<std::pair<double, double>>{{0, 0}, {1, 1}, {3, 2}, {4, 0}})
    EXPECT_DOUBLE_EQ(spline->at(t).translate[0], x) << "the spline passes through the key at t = " << t;
  // The velocity on either side of an interior key is the same (Catmull-Rom: C1), and it is
  // zero at the first and last key, where the motion comes from and goes to rest.
  // One-sided differences over e differ by about |x''| e (1e-6 here) where the curve is C1, and
  // by O(1) at a kink; 1e-4 lies between, far above rounding (u / e = 1e-10).
  const double e = 1e-6;
  for (double key : {1.0, 3.0}) {
    const double left = (spline->at(key).translate[0] - spline->at(key - e).translate[0]) / e;
    const double right = (spline->at(key + e).translate[0] - spline->at(key).translate[0]) / e;
    EXPECT_NEAR(left, right, 1e-4) << "at t = " << key;
  }
  EXPECT_NEAR((spline->at(e).translate[0] - spline->at(0).translate[0]) / e, 0, 1e-4);
  EXPECT_NEAR((spline->at(4).translate[0] - spline->at(4 - e).translate[0]) / e, 0, 1e-4);
}

TEST(Keyframes, RefusesKeysOutOfOrderOrNotFinite) {
  EXPECT_ERROR_NAMING(along_x({{0, 0}, {1, 1}, {1, 2}}, Keyframes::Interpolation::linear), "key 3 (t = 1)",
                      "key times must increase");
  EXPECT_ERROR_NAMING(along_x({{0, 0}, {NAN, 1}}, Keyframes::Interpolation::spline), "key 2", "finite");
  EXPECT_ERROR_NAMING(along_x({}, Keyframes::Interpolation::linear), "test", "at least one key");
}

// Galilean invariance: a column in a container that moves at a constant 0.5 m/s along x,
// with the fluid given that velocity, moves as the same column in a container at rest, seen
// from the moving container. Only rounding separates the two (the moving one takes each
// position into the container's frame and back), but a particle held at the contact distance
// is in contact or not by a hair, and rounding flips that: after 0.2 s no particle is 2% of a
// spacing from its place in the resting run (measured 0.8%), and the fluid's mean velocity is
// the container's to 1e-4 of it (in double precision; single precision below).
class MovingContainer : public ::testing::TestWithParam<std::string> {};

TEST_P(MovingContainer, CarriesTheFluidAsAContainerAtRest) {
  const std::string solver = GetParam();
  const double U = 0.5, dt = solver == "wcsph" ? 2e-4 : 0.004, end = 0.2;
  auto make = [&](Simulation& sim, bool moving) {
    // The container inside the domain, none of its faces on a face of the domain.
    sim.set_domain(Domain{{-0.05, -0.05, -0.05}, {0.3, 0.15, 0.25}});
    sim.set_kernel_radius(0.02);
    sim.set_timestep(dt);
    const double lo[3] = {0, 0, 0}, hi[3] = {0.1, 0.1, 0.1}, v[3] = {moving ? U : 0, 0, 0};
    add_lattice(sim, lo, hi, 0.01, v);
    sim.add_fix(fix("gravity", "gravity"));
    GivenParams tank = {{"shape", std::string("box")}, {"fluid", std::string("inside")}, {"lo", Vec3{0, 0, 0}},
                        {"hi", Vec3{0.1, 0.1, 0.2}}};
    if (moving) tank.push_back({"motion", along_x({{0, 0}, {1, U}}, Keyframes::Interpolation::linear)});
    sim.add_fix(fix("tank", "solid", tank));
    add_solver(sim, solver);
  };
  Simulation rest, moving;
  make(rest, false);
  make(moving, true);
  rest.run_until(end);
  moving.run_until(end);
  ASSERT_EQ(rest.particles().size(), moving.particles().size());
  const auto& A = rest.particles();
  const auto& B = moving.particles();
  // Memory order follows the particles' cells: match them by id.
  std::vector<std::size_t> in_b(B.size());
  for (std::size_t k = 0; k < B.size(); ++k) in_b[B.ids()[k]] = k;
  double worst = 0, mean_vx = 0;
  for (std::size_t i = 0; i < A.size(); ++i) {
    const std::size_t k = in_b[A.ids()[i]];
    worst = std::max({worst, std::abs(double(B.x()[k]) - U * moving.time() - A.x()[i]),
                      std::abs(double(B.y()[k]) - A.y()[i]), std::abs(double(B.z()[k]) - A.z()[i])});
    mean_vx += (B.vx()[k] - A.vx()[i]) / A.size();
  }
  if (sizeof(real) == sizeof(double) && solver != "dfsph") {
    EXPECT_LT(worst, 0.02 * 0.01);
    EXPECT_NEAR(mean_vx, U, 1e-4 * U);
  } else {
    // (DFSPH's solves stop at a tolerance, 1e-4 of the density: where a residual sits at it,
    // the two runs' iteration counts differ by one, so they agree to the solves' accuracy, not
    // to rounding: measured in double 0.1 spacing, 2026-11-29.)
    // Single precision rounds positions to 1e-8 m, and those differences grow in a column
    // that is not exactly at rest: each particle stays within a spacing of its place and the
    // fluid moves with the container to 1% of its speed.
    EXPECT_LT(worst, 0.01);
    EXPECT_NEAR(mean_vx, U, 1e-2 * U);
  }
}

INSTANTIATE_TEST_SUITE_P(BothSolvers, MovingContainer, ::testing::Values("pbf", "wcsph", "dfsph"));

// A piston (a box 4 spacings thick) moves at 0.3 m/s into a column at rest for 0.1 s: no
// particle is left behind its face, and every particle touching the face moves away from it
// at least at the piston's speed (no velocity into the wall relative to the wall).
class Piston : public ::testing::TestWithParam<std::string> {};

TEST_P(Piston, PushesTheFluidWithItsSpeed) {
  const std::string solver = GetParam();
  const double U = 0.3;
  Simulation sim;
  sim.set_domain(Domain{{0, 0, 0}, {0.3, 0.05, 0.2}});
  sim.set_kernel_radius(0.02);
  sim.set_timestep(solver == "wcsph" ? 2e-4 : 0.002);
  const double lo[3] = {0.04, 0, 0}, hi[3] = {0.3, 0.05, 0.1}, v[3] = {0, 0, 0};
  add_lattice(sim, lo, hi, 0.01, v);
  sim.add_fix(fix("gravity", "gravity"));
  sim.add_fix(fix("walls", "box"));
  sim.add_fix(fix("piston", "solid", {{"shape", std::string("box")}, {"lo", Vec3{0, 0, 0}},
                                      {"hi", Vec3{0.04, 0.05, 0.2}},
                                      {"motion", along_x({{0, 0}, {1, U}}, Keyframes::Interpolation::linear)}}));
  add_solver(sim, solver);
  sim.run_until(0.1);
  // The solid keeps particles half a spacing (the default contact distance) off its face.
  const double face = 0.04 + U * sim.time(), contact = face + 0.005;
  const auto& P = sim.particles();
  // Particles in contact move with the wall; the first layer, within a spacing of the face,
  // on average within 10%.
  int first_layer = 0;
  double first_layer_vx = 0;
  // Under DFSPH the solid projects once a step (after the drift), where PBF and WCSPH project
  // again in the constraints: a single projection leaves the map's reading error, micrometres
  // (engine/geometry/solid_map.hpp), which the bound allows there.
  const double behind = solver == "dfsph" ? 1e-5 : 1e-6;
  for (std::size_t i = 0; i < P.size(); ++i) {
    ASSERT_GE(P.x()[i], contact - behind) << "particle " << P.ids()[i];
    if (P.x()[i] < contact + 1e-5) EXPECT_GE(P.vx()[i], U * (1 - 1e-3)) << "particle " << P.ids()[i];
    if (P.x()[i] < face + 0.01) ++first_layer, first_layer_vx += P.vx()[i];
  }
  ASSERT_GT(first_layer, 0);
  // The layer beyond contact is pushed by the constraint, not held: it may lag or lead a little;
  // a piston that let fluid through (0) or kicked it (2U) is far outside 10%.
  EXPECT_NEAR(first_layer_vx / first_layer, U, 0.1 * U);
}

INSTANTIATE_TEST_SUITE_P(BothSolvers, Piston, ::testing::Values("pbf", "wcsph", "dfsph"));

// A cube spinning about its centre with a no-slip wall: every particle touching one of its
// faces (more than a map cell from its edges, where the map is exact) moves along it with the wall's velocity
// omega x r. The wall's velocity over a step is the chord of its points' arcs, so it differs
// from omega x r by omega dt / 2 relatively (0.2% here): the particles' must agree within 1%
// of the face's largest speed. Skipped in single precision, where the name says why.
#if PBF_REAL_IS_FLOAT
#define SPINNING_CUBE_TEST ASpinningNoSlipCubeDragsTheFluidTouchingIt_SkippedInSinglePrecisionWhereNoParticleStaysOnAFace
#else
#define SPINNING_CUBE_TEST ASpinningNoSlipCubeDragsTheFluidTouchingIt
#endif
TEST(MovingSolid, SPINNING_CUBE_TEST) {
  Simulation sim;
  sim.set_domain(Domain{{0, 0, 0}, {0.2, 0.2, 0.2}});
  sim.set_kernel_radius(0.02);
  sim.set_timestep(0.002);
  const double lo[3] = {0, 0, 0}, hi[3] = {0.2, 0.2, 0.2}, v[3] = {0, 0, 0};
  add_lattice(sim, lo, hi, 0.01, v);
  sim.add_fix(fix("walls", "box"));
  // 90 degrees a second about z; the faces (at 0.07 and 0.13) half a spacing from the lattice's
  // sites, so that the fluid starts in contact with them.
  const double omega = M_PI / 2, half = 0.03, c = 0.1;
  std::vector<Keyframes::Key> keys = {{0, Pose{{0, 0, 0}, {0, 0, 0}}}, {1, Pose{{0, 0, 0}, {0, 0, 90}}}};
  sim.add_fix(fix("cube", "solid", {{"shape", std::string("box")}, {"lo", Vec3{c - half, c - half, c - half}},
                                    {"hi", Vec3{c + half, c + half, c + half}}, {"no_slip", true},
                                    {"pivot", Vec3{c, c, c}},
                                    {"motion", std::make_shared<Keyframes>(keys, Keyframes::Interpolation::linear,
                                                                           "spin")}}));
  // In single precision the wall's density lifts every particle off the faces within 20 steps,
  // leaving none in contact to check (seen 2026-11-23, with the Wendland kernel; issue 10's note).
  if (sizeof(real) == 4) GTEST_SKIP() << "no particle stays in contact with the faces in single precision";
  sim.add_fix(fix("pbf", "pbf"));
  sim.run(50);
  const double angle = omega * sim.time(), cs = std::cos(angle), sn = std::sin(angle);
  const auto& P = sim.particles();
  int touching = 0;
  for (std::size_t i = 0; i < P.size(); ++i) {
    const double r[3] = {P.x()[i] - c, P.y()[i] - c, P.z()[i] - c};
    const double body[3] = {cs * r[0] + sn * r[1], -sn * r[0] + cs * r[1], r[2]};  // R^T r
    // The face it touches (the one it is outside of, at the default contact distance of half
    // a spacing), away from the edges by h.
    const double contact = half + 0.005;
    int face = -1;
    for (int a = 0; a < 3; ++a)
      if (std::abs(body[a]) > contact - 1e-5) face = a;
    if (face < 0 || std::abs(body[face]) > contact + 1e-5) continue;
    bool inner = true;
    for (int a = 0; a < 3; ++a) inner = inner && (a == face || std::abs(body[a]) < half - 0.006);
    if (!inner) continue;
    ++touching;
    double n[3] = {0, 0, 0};
    n[face] = body[face] > 0 ? 1 : -1;
    const double nw[3] = {cs * n[0] - sn * n[1], sn * n[0] + cs * n[1], n[2]};  // R n
    const double wall[3] = {-omega * r[1], omega * r[0], 0};
    double rel[3], rn = 0;
    const double vel[3] = {P.vx()[i], P.vy()[i], P.vz()[i]};
    for (int a = 0; a < 3; ++a) rel[a] = vel[a] - wall[a];
    for (int a = 0; a < 3; ++a) rn += rel[a] * nw[a];
    const double tangential = std::hypot(rel[0] - rn * nw[0], rel[1] - rn * nw[1], rel[2] - rn * nw[2]);
    EXPECT_LT(tangential, 0.01 * omega * half * std::sqrt(2.0)) << "particle " << P.ids()[i];
  }
  EXPECT_GT(touching, 0);  // the count on the faces depends on how far the wall density holds particles off
}

// cfl counts a moving wall's speed: a wall at 20 m/s keeps the step below courant h / 20.
TEST(MovingSolid, TimeStepControlCountsTheWallsSpeed) {
  Simulation sim;
  sim.set_domain(Domain{{0, 0, 0}, {1, 0.1, 0.2}});
  sim.set_kernel_radius(0.02);
  sim.set_timestep(0.01);
  const double lo[3] = {0.5, 0, 0}, hi[3] = {0.6, 0.1, 0.1}, v[3] = {0, 0, 0};
  add_lattice(sim, lo, hi, 0.01, v);
  sim.add_fix(fix("paddle", "solid", {{"shape", std::string("box")}, {"lo", Vec3{0, 0, 0}},
                                      {"hi", Vec3{0.04, 0.1, 0.2}},
                                      {"motion", along_x({{0, 0}, {1, 20}}, Keyframes::Interpolation::linear)}}));
  sim.add_fix(fix("pbf", "pbf"));
  sim.add_fix(fix("cfl", "cfl", {{"courant", 0.4}, {"sound_speed", 1e-9}}));
  sim.run(2);
  EXPECT_LE(sim.timestep(), 0.4 * 0.02 / 20 * (1 + 1e-9));
  EXPECT_GE(sim.timestep(), 0.4 * 0.02 / 20 * 0.99);  // the bound itself: nothing else limits the step here
}

// A paddle driven by a Lua function, and one by keyframes, continue bit for bit from a restart.
TEST(MovingSolid, ContinuesBitForBitFromARestart) {
  TempDir dir("motion-restart");
  write_file(dir.path() / "paddle.lua", R"(
if var.restart then pbf.read_restart(var.restart) else
  pbf.domain{lo = {0, 0, 0}, hi = {0.4, 0.05, 0.2}}
  pbf.kernel_radius(0.02)
  pbf.timestep(0.002)
  pbf.lattice{lo = {0.05, 0, 0}, hi = {0.4, 0.05, 0.1}, spacing = 0.01}
end
local motion = function(t) return {translate = {0.02 * math.sin(8 * t), 0, 0}} end
if var.keys then motion = pbf.keyframes{{t = 0}, {t = 0.1, translate = {0.02, 0, 0}}, {t = 0.3, rotate = {0, 5, 0}}, interpolation = "spline"} end
pbf.fix("gravity", "gravity", {})
pbf.fix("pbf", "pbf", {})
pbf.fix("walls", "box", {})
pbf.fix("paddle", "solid", {shape = "box", lo = {-0.05, 0, 0}, hi = {0.03, 0.05, 0.2}, motion = motion, pivot = {0, 0, 0}})
pbf.fix("restarts", "restart", {path = var.out .. "/r.*.restart", every = 40, keep = 5})
pbf.run(120 - pbf.step())
pbf.write_restart(var.final)
)");
  for (const std::string keys : {"", " -v keys=1"}) {
    auto args = [&](const std::string& final) {
      return fmt::format("run {} -v out={} -v final={}{}", (dir.path() / "paddle.lua").string(),
                         (dir.path() / "out").string(), (dir.path() / final).string(), keys);
    };
    auto straight = run_engine(args("straight.final"));
    ASSERT_EQ(straight.code, 0) << straight.output;
    auto continued = run_engine(args("continued.final") + " -v restart=" + (dir.path() / "out/r.40.restart").string());
    ASSERT_EQ(continued.code, 0) << continued.output;
    EXPECT_EQ(continued.output.find("warning"), std::string::npos) << continued.output;
    EXPECT_TRUE(read_file(dir.path() / "straight.final") == read_file(dir.path() / "continued.final")) << keys;
  }
}

// Bad motions: each is refused with one message naming what is wrong and where.
TEST(MovingSolid, RefusesBadMotionsByName) {
  TempDir dir("motion-bad");
  auto run_with = [&](const std::string& motion) {
    write_file(dir.path() / "bad.lua", R"(
pbf.domain{lo = {0, 0, 0}, hi = {0.3, 0.05, 0.2}}
pbf.kernel_radius(0.02)
pbf.timestep(0.002)
pbf.lattice{lo = {0.1, 0, 0}, hi = {0.3, 0.05, 0.1}, spacing = 0.01}
pbf.fix("pbf", "pbf", {})
pbf.fix("walls", "box", {})
pbf.fix("paddle", "solid", {shape = "box", lo = {0, 0, 0}, hi = {0.04, 0.05, 0.2}, motion = )" +
                                              motion + R"(})
pbf.run(5)
)");
    return run_engine("run " + (dir.path() / "bad.lua").string());
  };
  struct Case {
    std::string motion, says;
  };
  const std::vector<Case> cases = {
      {"function(t) error('no pose here') end", "no pose here"},
      {"function(t) return {translate = {0/0, 0, 0}} end", "translate[1] = nan"},
      {"function(t) return 3 end", "returned a number, not a table"},
      {"function(t) return {translate = {1, 2}} end", "'translate' must be a vector"},
      {"pbf.keyframes{{t = 1}, {t = 0.5}}", "key 2 (t = 0.5) is not after key 1 (t = 1)"},
      {"pbf.keyframes{{t = 0}, interpolation = 'cubic'}", "'interpolation' must be \"linear\" or \"spline\""},
      {"pbf.keyframes{{t = 0}, speed = 2}", "unknown entry 'speed'"},
      {"pbf.keyframes{{t = 'soon'}}", "key 1: 't' must be a number"},
      {"{0, 1, 2}", "must be of type motion"}};
  for (const auto& c : cases) {
    const auto r = run_with(c.motion);
    EXPECT_EQ(r.code, 1) << c.motion << "\n" << r.output;
    EXPECT_NE(r.output.find(c.says), std::string::npos) << c.motion << "\n" << r.output;
    EXPECT_NE(r.output.find("bad.lua:"), std::string::npos) << c.motion << "\n" << r.output;
  }
  // A moving plane is refused: its map covers only the domain.
  Simulation sim;
  EXPECT_ERROR_NAMING(fix("floor", "solid", {{"shape", std::string("plane")}, {"point", Vec3{0, 0, 0}},
                                             {"normal", Vec3{0, 0, 1}},
                                             {"motion", along_x({{0, 0}}, Keyframes::Interpolation::linear)}}),
                      "plane", "a plane cannot move");
}
