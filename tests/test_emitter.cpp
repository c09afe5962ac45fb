// Fluid that enters: the emitter fix. Its flow rate is measured, not counted: the mass that
// crosses a plane a few spacings downstream of the opening over a second must be the set
// one, rho0 A (U . n), within 2%. The particles enter in layers at the distance L = N V / A
// (engine/fixes/emitter.cpp), each standing for its rest volume V = m / rho0; so the flux
// carries the set rate exactly, and the 2% allow for what is in flight at the window's ends:
// a layer of N particles crossing, about N m / (rho0 A U) = L / U = 0.01 s of a 1 s window.
#include <gtest/gtest.h>

#include <omp.h>

#include <cmath>
#include <string>
#include <vector>

#include "engine/core/simulation.hpp"
#include "engine/io/restart.hpp"
#include "engine/registry/style_registry.hpp"
#include "pipelines.hpp"
#include "test_util.hpp"

using namespace pbf;
using namespace pbf::test;

namespace {

// An empty tank 0.3 x 0.3 x 0.4 m, spacing 1 cm, h = 2 cm; a jet downward from z = 0.35 m
// through a disc of radius 3 cm (or a 6 x 4 cm rectangle) at 1 m/s, with the solver's pipeline.
void jet_scene(Simulation& sim, const std::string& solver, const std::string& shape) {
  sim.set_domain(Domain{{0, 0, 0}, {0.3, 0.3, 0.4}});
  sim.set_kernel_radius(0.02);
  const auto& styles = StyleRegistry::builtin();
  GivenParams jet = {{"shape", shape},           {"center", Vec3{0.15, 0.15, 0.35}}, {"normal", Vec3{0, 0, -2}},
                     {"speed", 1.0},             {"spacing", 0.01}};
  if (shape == "disc") jet.push_back({"radius", 0.03});
  else jet.push_back({"size", Vec2{0.06, 0.04}});
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

}  // namespace

class EmitterRate : public ::testing::TestWithParam<std::tuple<const char*, const char*>> {};

TEST_P(EmitterRate, TheMassCrossingAPlaneDownstreamIsTheSetRate) {
  const auto [solver, shape] = GetParam();
  Simulation sim;
  jet_scene(sim, solver, shape);
  const double area = std::string(shape) == "disc" ? M_PI * 0.03 * 0.03 : 0.06 * 0.04;
  const double set_rate = 1000 * area * 1.0;  // rho0 A U, kg/s
  const double plane = 0.35 - 0.03;             // three spacings downstream
  const double t0 = 0.1, window = 1.0;
  sim.run_until(t0);
  std::vector<real> z_before;
  double crossed = 0;
  const auto& P = sim.particles();
  while (sim.time() < t0 + window - 1e-9) {
    z_before.assign(static_cast<std::size_t>(P.next_id()), real(1));  // new ones start above
    for (std::size_t i = 0; i < P.size(); ++i) z_before[static_cast<std::size_t>(P.ids()[i])] = P.z()[i];
    sim.run(1);
    for (std::size_t i = 0; i < P.size(); ++i) {
      const auto id = static_cast<std::size_t>(P.ids()[i]);
      if (id < z_before.size() && z_before[id] >= real(plane) && P.z()[i] < real(plane)) crossed += P.mass()[i];
    }
  }
  const double rate = crossed / window;
  std::printf("%s %s: %.5g kg/s, set %.5g\n", solver, shape, rate, set_rate);
  EXPECT_NEAR(rate, set_rate, 0.02 * set_rate) << solver << " " << shape << ": " << rate << " kg/s against " << set_rate;
}

INSTANTIATE_TEST_SUITE_P(BothSolvers, EmitterRate,
                         ::testing::Combine(::testing::Values("pbf", "wcsph"), ::testing::Values("disc", "rectangle")),
                         [](const auto& info) {
                           return std::string(std::get<0>(info.param)) + "_" + std::get<1>(info.param);
                         });
