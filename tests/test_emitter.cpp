// Fluid that enters: the emitter fix. Its flow rate is measured, not counted: the mass that
// crosses a plane a few spacings downstream of the opening over a second must be the set
// one, rho0 A (U . n), within 2%. The particles enter in layers at the distance L = N V / A
// (engine/fixes/emitter.cpp), each standing for its rest volume V = m / rho0; so the flux
// carries the set rate exactly, and the 2% allow for what is in flight at the window's ends:
// a layer of N particles crossing, about N m / (rho0 A U) = L / U = 0.01 s of a 1 s window.
// The same for a velocity that is a function of time (a ramp) or of the place (a profile),
// which also enters at every site at the function's velocity; and the function's errors,
// through the binary.
#include <gtest/gtest.h>

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "engine/core/simulation.hpp"
#include "engine/geometry/space_time_function.hpp"
#include "engine/io/restart.hpp"
#include "engine/registry/style_registry.hpp"
#include "engine/sph/lattice.hpp"
#include "pipelines.hpp"
#include "test_util.hpp"

using namespace pbf;
using namespace pbf::test;

namespace {

// An empty tank 0.3 x 0.3 x 0.4 m, spacing 1 cm, h = 2 cm; a jet downward from z = 0.35 m
// through a disc of radius 3 cm (or a rectangle, 6 x 4 cm unless `size` says) at 1 m/s (or
// the `inflow` given), with the solver's pipeline.
void jet_scene(Simulation& sim, const std::string& solver, const std::string& shape,
               const GivenParams& inflow = {{"speed", 1.0}}, const Vec2& size = {0.06, 0.04}) {
  sim.set_domain(Domain{{0, 0, 0}, {0.3, 0.3, 0.4}});
  sim.set_kernel_radius(0.02);
  const auto& styles = StyleRegistry::builtin();
  GivenParams jet = {
      {"shape", shape}, {"center", Vec3{0.15, 0.15, 0.35}}, {"normal", Vec3{0, 0, -2}}, {"spacing", 0.01}};
  jet.insert(jet.end(), inflow.begin(), inflow.end());
  if (shape == "disc") jet.push_back({"radius", 0.03});
  else jet.push_back({"size", size});
  if (solver == "pbf") {
    sim.set_timestep(0.001);
    sim.add_fix(styles.make_fix("gravity", "gravity", {}));
    sim.add_fix(styles.make_fix("pbf", "pbf", {}));
  } else {
    sim.set_timestep(0.0002);  // c0 = 20 m/s given: 0.2 h / c0
    sim.add_fix(styles.make_fix("gravity", "gravity", {}));
    sim.add_fix(styles.make_fix("integrator", "leapfrog", {}));
    sim.add_fix(styles.make_fix("wcsph", "wcsph", {{"sound_speed", 20.0}}));
    sim.add_fix(styles.make_fix("viscosity", "sph_viscosity", {}));
  }
  sim.add_fix(styles.make_fix("walls", "box", {}));
  sim.add_fix(styles.make_fix("jet", "emitter", jet));
  sim.add_compute(styles.make_compute("in", "flow", {{"fix", std::string("jet")}}));
}

// The mass that crosses the plane z = 0.32 m (three spacings below the opening) downward
// between t0 and t1, run step by step.
double mass_crossing(Simulation& sim, double t0, double t1) {
  const real plane(0.35 - 0.03);
  sim.run_until(t0);
  std::vector<real> z_before;
  double crossed = 0;
  const auto& P = sim.particles();
  while (sim.time() < t1 - 1e-9) {
    z_before.assign(static_cast<std::size_t>(P.next_id()), real(1));  // new ones start above
    for (std::size_t i = 0; i < P.size(); ++i) z_before[static_cast<std::size_t>(P.ids()[i])] = P.z()[i];
    sim.run(1);
    for (std::size_t i = 0; i < P.size(); ++i) {
      const auto id = static_cast<std::size_t>(P.ids()[i]);
      if (id < z_before.size() && z_before[id] >= plane && P.z()[i] < plane) crossed += P.mass()[i];
    }
  }
  return crossed;
}

// A test's velocity function: f(t, x) as a C++ function, as the engine sees a Lua one.
class Function : public SpaceTimeFunction {
 public:
  explicit Function(std::function<Vec3(double, const Vec3&)> f) : f_(std::move(f)) {}
  Vec3 at(double t, const Vec3& x) const override { return f_(t, x); }
  bool constant() const override { return false; }
  std::string description() const override { return "the test's function"; }

 private:
  std::function<Vec3(double, const Vec3&)> f_;
};

// f as the parameter `name` (speed or velocity).
GivenParams given(const std::string& name, std::function<Vec3(double, const Vec3&)> f) {
  return {{name, SpaceTimeFunctionPtr(std::make_shared<Function>(std::move(f)))}};
}

}  // namespace

class EmitterRate : public ::testing::TestWithParam<std::tuple<const char*, const char*>> {};

TEST_P(EmitterRate, TheMassCrossingAPlaneDownstreamIsTheSetRate) {
  const auto [solver, shape] = GetParam();
  Simulation sim;
  jet_scene(sim, solver, shape);
  const double area = std::string(shape) == "disc" ? M_PI * 0.03 * 0.03 : 0.06 * 0.04;
  const double set_rate = 1000 * area * 1.0;  // rho0 A U, kg/s
  const double rate = mass_crossing(sim, 0.1, 1.1) / 1.0;
  std::printf("%s %s: %.5g kg/s, set %.5g\n", solver, shape, rate, set_rate);
  EXPECT_NEAR(rate, set_rate, 0.02 * set_rate) << solver << " " << shape << ": " << rate << " kg/s, set " << set_rate;
}

INSTANTIATE_TEST_SUITE_P(BothSolvers, EmitterRate,
                         ::testing::Combine(::testing::Values("pbf", "wcsph"), ::testing::Values("disc", "rectangle")),
                         [](const auto& info) {
                           return std::string(std::get<0>(info.param)) + "_" + std::get<1>(info.param);
                         });

// An opening that fluid covers waits for room, says so once, and emits as soon as the fluid
// has gone (here: removed between runs), without overlapping it meanwhile.
TEST(Emitter, WaitsForRoomWhereFluidCoversTheOpeningAndSaysSoOnce) {
  Simulation sim;
  sim.set_domain(Domain{{0, 0, 0}, {0.2, 0.2, 0.2}});
  sim.set_kernel_radius(0.02);
  sim.set_timestep(0.001);
  const double lo[3] = {0.05, 0.05, 0.05}, hi[3] = {0.15, 0.15, 0.1}, rest[3] = {0, 0, 0};
  add_lattice(sim, lo, hi, 0.01, rest);  // a block at rest, no gravity, over the opening
  const auto& styles = StyleRegistry::builtin();
  sim.add_fix(styles.make_fix("pbf", "pbf", {}));
  sim.add_fix(styles.make_fix("walls", "box", {}));
  sim.add_fix(styles.make_fix("jet", "emitter",
                              {{"center", Vec3{0.1, 0.1, 0.075}}, {"normal", Vec3{0, 0, 1}}, {"size", Vec2{0.04, 0.04}},
                               {"speed", 0.5}}));
  sim.add_compute(styles.make_compute("in", "flow", {{"fix", std::string("jet")}}));
  LogCapture log;
  sim.run(20);
  std::vector<double> v;
  sim.find_compute("in")->evaluate(sim, v);
  EXPECT_EQ(v[0], 0.0);
  EXPECT_EQ(sim.particles().size(), 500u);
  EXPECT_EQ(log.count("emitter 'jet': fluid stands in front of the opening"), 1) << log.text();
  // The block gone, the layer held back enters at once (it waited at the opening's plane).
  std::vector<char> all(sim.particles().size(), 1);
  sim.particles().remove(all);
  sim.run(1);
  sim.find_compute("in")->evaluate(sim, v);
  EXPECT_EQ(v[0], 16.0);  // a layer of 4 x 4
  EXPECT_EQ(log.count("emitter 'jet': fluid stands in front of the opening"), 1);
}

// U(t) = U0 min(t / T, 1), U0 = 1 m/s, T = 0.5 s. The fluid that crosses the plane at t left
// the opening at t_e, a free fall of d = 3 cm earlier: t_e + tau(U(t_e)) = t, with
// tau(U) = (sqrt(U^2 + 2 g d) - U) / g. So what crosses between t0 and t1 is what entered
// between t_e(t0) and t_e(t1), rho0 A (F(t_e(t1)) - F(t_e(t0))), F the integral of U from 0.
TEST(EmitterFunction, ARampsMassCrossingAPlaneDownstreamIsItsIntegral) {
  const double U0 = 1, T = 0.5, g = 9.81, d = 0.03, area = 0.06 * 0.04;
  auto U = [&](double t) { return U0 * std::min(t / T, 1.0); };
  auto F = [&](double t) { return t < T ? U0 * t * t / (2 * T) : U0 * (T / 2 + t - T); };
  auto left_at = [&](double t) {  // by fixed-point iteration (it contracts: |dtau/dt_e| < 1/5)
    double te = t;
    for (int k = 0; k < 50; ++k) te = t - (std::sqrt(U(te) * U(te) + 2 * g * d) - U(te)) / g;
    return te;
  };
  Simulation sim;
  jet_scene(sim, "pbf", "rectangle", given("speed", [&](double t, const Vec3&) { return Vec3{U(t), 0, 0}; }));
  const double t0 = 0.1, t1 = 1.1;
  const double crossed = mass_crossing(sim, t0, t1);
  const double expected = 1000 * area * (F(left_at(t1)) - F(left_at(t0)));
  std::printf("ramp: %.5g kg crossed, %.5g entered in the matching times\n", crossed, expected);
  EXPECT_NEAR(crossed, expected, 0.02 * expected);
}

// A parabolic profile across the rectangle's side a = 0.08 m (along x), U = U_max (1 - (2 a' /
// a)^2) at the offset a' from the centre, U_max = 1.5 m/s: the set rate is rho0 times the
// integral of U . n over the opening, rho0 (2/3) U_max a b = 3.2 kg/s (the 8 sites across a
// give the midpoint rule's sum, 1 / (3 8^2) U_max = 0.8% more).
Vec3 parabola(const Vec3& x) {
  const double across = (x[0] - 0.15) / 0.04;
  return {0, 0, -1.5 * (1 - across * across)};
}

TEST(EmitterFunction, AProfilesMassCrossingAPlaneDownstreamIsItsIntegral) {
  Simulation sim;
  jet_scene(sim, "pbf", "rectangle", given("velocity", [](double, const Vec3& x) { return parabola(x); }),
            {0.08, 0.04});
  const double set_rate = 1000 * (2.0 / 3.0) * 1.5 * 0.08 * 0.04;
  const double rate = mass_crossing(sim, 0.1, 1.1) / 1.0;
  std::printf("profile: %.5g kg/s, set %.5g\n", rate, set_rate);
  EXPECT_NEAR(rate, set_rate, 0.02 * set_rate);
}

// Each site lets its particles in at its own velocity and rate: with a leapfrog and no force
// they keep the velocity they entered with, so after n steps every particle moves at the
// profile's U at its site, and the site with U_k has let in 1 + floor(n U_k dt / L) of them
// (its first at the first step, its next each time it advanced L = N m / (rho0 A)).
TEST(EmitterFunction, EachSiteLetsInAtItsVelocityAndItsRate) {
  Simulation sim;
  sim.set_domain(Domain{{0, 0, 0}, {0.3, 0.3, 0.4}});
  sim.set_kernel_radius(0.02);
  sim.set_timestep(0.001);
  const auto& styles = StyleRegistry::builtin();
  sim.add_fix(styles.make_fix("integrator", "leapfrog", {}));
  GivenParams jet = {{"center", Vec3{0.15, 0.15, 0.35}}, {"normal", Vec3{0, 0, -1}}, {"size", Vec2{0.08, 0.04}},
                     {"spacing", 0.01}};
  jet.push_back(given("velocity", [](double, const Vec3& x) { return parabola(x); })[0]);
  sim.add_fix(styles.make_fix("jet", "emitter", jet));
  const int steps = 100;
  sim.run(steps);
  const auto& P = sim.particles();
  ASSERT_GT(P.size(), 0u);
  const double L = 32 * double(P.mass()[0]) / 1000 / (0.08 * 0.04);
  std::map<std::pair<long, long>, int> count;  // by site: its cell across x and y
  for (std::size_t i = 0; i < P.size(); ++i) {
    const Vec3 x = {double(P.x()[i]), double(P.y()[i]), double(P.z()[i])};
    const Vec3 U = parabola(x);
    EXPECT_NEAR(P.vx()[i], 0, 1e-12);
    EXPECT_NEAR(P.vy()[i], 0, 1e-12);
    EXPECT_NEAR(P.vz()[i], U[2], 1e-5) << "at x = " << x[0];
    ++count[{std::lround((x[0] - 0.11) / 0.01 - 0.5), std::lround((x[1] - 0.13) / 0.01 - 0.5)}];
  }
  ASSERT_EQ(count.size(), 32u);
  for (const auto& [site, n] : count) {
    const double advanced = steps * -parabola({0.11 + (double(site.first) + 0.5) * 0.01, 0, 0})[2] * 0.001 / L;
    EXPECT_LE(n - 1, advanced + 1e-6) << "site " << site.first << ", " << site.second;
    EXPECT_GT(n - 1, advanced - 1 - 1e-6) << "site " << site.first << ", " << site.second;
  }
}

// A function's errors stop the run with one message that names the emitter, the parameter
// and the script's line (the function's own, for an error it raises), and exit code 1.
TEST(EmitterFunction, RefusesBadFunctionsByName) {
  TempDir dir("emitter-bad");
  auto run_with = [&](const std::string& inflow) {
    write_file(dir / "bad.lua", R"(pbf.domain{lo = {0, 0, 0}, hi = {0.2, 0.2, 0.2}}
pbf.kernel_radius(0.02)
pbf.timestep(0.001)
pbf.fix("gravity", "gravity", {})
pbf.fix("pbf", "pbf", {})
pbf.fix("walls", "box", {})
pbf.fix("jet", "emitter", {center = {0.1, 0.1, 0.15}, normal = {0, 0, -1}, size = {0.02, 0.02}, spacing = 0.01,
                           )" + inflow + R"(})
pbf.run(5)
)");
    return run_engine("run " + (dir / "bad.lua").string(), "2>&1 1>/dev/null");  // the message alone
  };
  struct Case {
    std::string inflow, says;
  };
  const std::string fn = "function(t, x, y, z) ";
  const std::vector<Case> cases = {
      {"velocity = " + fn + "error('no inflow here') end", "bad.lua:8: no inflow here"},
      {"velocity = " + fn + "return 2 end", "returned a number, not a vector {x, y, z}"},
      {"velocity = " + fn + "end", "returned a nil, not a vector {x, y, z}"},
      {"velocity = " + fn + "return {0, -1} end", "returned a table of 2 values, not a vector {x, y, z}"},
      {"velocity = " + fn + "return {0, 0, 'down'} end", "component 3 is a string"},
      {"velocity = " + fn + "return {0, 0, 1} end", "gave {0, 0, 1}: its part along the normal, -1 m/s, must be >= 0"},
      {"velocity = " + fn + "return {0/0, 0, -1} end", "gave {nan, 0, -1}: a velocity must be finite"},
      {"velocity = " + fn + "return {0, 0, t > 0.0025 and 0/0 or -1} end", "at t = 0.0035 s"},
      {"velocity = " + fn + "return {1e7, 0, -1} end", "a velocity must be at most 1e6 m/s"},
      {"velocity = " + fn + "coroutine.yield() end", "yield"},
      {"speed = " + fn + "return {0, 0, 1} end",
       "at t = 0.0005 s, (x, y, z) = (0.095, 0.105, 0.15) returned a table, not a number"},
      {"speed = " + fn + "return -0.5 end", "gave -0.5 m/s: a speed must be >= 0"},
      {"velocity = {0, 0, 1}", "parameter 'velocity' (0, 0, 1) points along the opening or back into it"},
      {"speed = 'fast'", "parameter 'speed' must be of type number or function(t, x, y, z), got string"},
      {"velocity = 2", "parameter 'velocity' must be of type vector {x, y, z} or function(t, x, y, z), got integer"}};
  for (const auto& c : cases) {
    const auto r = run_with(c.inflow);
    EXPECT_EQ(r.code, 1) << c.inflow << "\n" << r.output;
    EXPECT_NE(r.output.find(c.says), std::string::npos) << c.inflow << "\n" << r.output;
    EXPECT_NE(r.output.find("bad.lua:"), std::string::npos) << c.inflow << "\n" << r.output;
    EXPECT_NE(r.output.find("fix 'jet' (emitter)"), std::string::npos) << c.inflow << "\n" << r.output;
    const std::string parameter = c.inflow.substr(0, c.inflow.find(' '));  // speed or velocity
    EXPECT_NE(r.output.find("parameter '" + parameter + "'"), std::string::npos) << c.inflow << "\n" << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << c.inflow << "\n" << r.output;
  }
}

// The function is not saved: the script gives it again, and the run goes on bit for bit (a
// profile that grows in time, with an inlet zone, so that the sites are at different
// distances at the restart, and the zone's velocities come from the function).
TEST(EmitterFunction, ContinuesBitForBitFromARestart) {
  TempDir dir("emitter-restart");
  write_file(dir / "inlet.lua", R"(
if var.restart then pbf.read_restart(var.restart) else
  pbf.domain{lo = {0, 0, 0}, hi = {0.2, 0.1, 0.2}}
  pbf.kernel_radius(0.02)
  pbf.timestep(0.002)
  pbf.lattice{lo = {0, 0, 0}, hi = {0.2, 0.1, 0.04}, spacing = 0.01}
end
pbf.fix("gravity", "gravity", {})
pbf.fix("pbf", "pbf", {})
pbf.fix("walls", "box", {})
local function inflow(t, x, y, z)
  local across = (y - 0.05) / 0.03
  return {0.1 * across, 0, -(0.3 + 5 * t) * (1 - across * across)}
end
pbf.fix("jet", "emitter", {center = {0.1, 0.05, 0.12}, normal = {0, 0, -1}, size = {0.04, 0.06}, buffer = 0.02,
                           velocity = inflow})
pbf.compute("in", "flow", {fix = "jet"})
pbf.fix("restarts", "restart", {path = var.out .. "/r.*.restart", every = 40, keep = 5})
pbf.run(120 - pbf.step())
assert(pbf.value("in").count > 100, pbf.value("in").count)
pbf.write_restart(var.final)
)");
  auto args = [&](const std::string& final) {
    return fmt::format("run {} -v out={} -v final={}", (dir / "inlet.lua").string(), (dir / "out").string(),
                       (dir / final).string());
  };
  auto straight = run_engine(args("straight.final"));
  ASSERT_EQ(straight.code, 0) << straight.output;
  auto continued = run_engine(args("continued.final") + " -v restart=" + (dir / "out/r.40.restart").string());
  ASSERT_EQ(continued.code, 0) << continued.output;
  EXPECT_EQ(continued.output.find("warning"), std::string::npos) << continued.output;
  EXPECT_TRUE(read_file(dir / "straight.final") == read_file(dir / "continued.final"));
}
