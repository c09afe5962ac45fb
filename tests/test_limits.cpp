// Legal but absurd values are refused before they cost anything: runs that would not end,
// kernel radii that reach no neighbour or thousands, lattices that would not fit in memory or
// hold nothing, domains positions cannot resolve, a start state one step would wreck.
#include <gtest/gtest.h>

#include <chrono>
#include <string>

#include "engine/core/error.hpp"
#include "engine/core/simulation.hpp"
#include "engine/registry/style_registry.hpp"
#include "engine/sph/lattice.hpp"

using namespace pbf;

namespace {

// The message of the pbf::Error `f` throws ("" if none).
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// A 0.2 m box, h = 0.02 m, dt = 0.002 s; with `particles`, a 1000-particle lattice at spacing
// h/2 and the PBF pipeline.
void make_scene(Simulation& sim, bool particles = true) {
  sim.set_domain(Domain{{0, 0, 0}, {0.2, 0.2, 0.2}});
  sim.set_kernel_radius(0.02);
  sim.set_timestep(0.002);
  if (!particles) return;
  const double lo[3] = {0, 0, 0}, hi[3] = {0.1, 0.1, 0.1}, v[3] = {0, 0, 0};
  add_lattice(sim, lo, hi, 0.01, v);
  for (const char* style : {"gravity", "pbf", "box"}) sim.add_fix(StyleRegistry::builtin().make_fix(style, style, {}));
}

void lattice(Simulation& sim, double spacing, const double velocity[3] = nullptr) {
  const double lo[3] = {0, 0, 0}, hi[3] = {0.1, 0.1, 0.1}, still[3] = {0, 0, 0};
  add_lattice(sim, lo, hi, spacing, velocity ? velocity : still);
}

}  // namespace

TEST(Limits, RunsThatWouldNotEndAreRefusedBeforeTheFirstStep) {
  Simulation sim;
  make_scene(sim);
  EXPECT_NE(error_of([&] { sim.run_until(1e308); }).find("run_until(1e+308): from t = 0 s at dt = 0.002 s that is"),
            std::string::npos);
  EXPECT_NE(error_of([&] { sim.run(2000000000); }).find("more than 1e+09"), std::string::npos);
  sim.set_timestep(1e-300);
  EXPECT_NE(error_of([&] { sim.run_until(1); }).find("steps, more than 1e+09"), std::string::npos);
  EXPECT_EQ(sim.step(), 0);  // nothing ran
  // A clock so far along that the step no longer moves it.
  sim.set_timestep(0.002);
  sim.set_clock({0, 0, 1e20});
  EXPECT_NE(error_of([&] { sim.run(1); }).find("vanishes against the time"), std::string::npos);
}

TEST(Limits, KernelRadiusMustReachOneToTenSpacings) {
  Simulation sim;
  make_scene(sim, false);
  sim.set_kernel_radius(20);  // 2000 spacings: the mass rule alone would walk 6e10 lattice sites
  const auto start = std::chrono::steady_clock::now();
  EXPECT_NE(error_of([&] { lattice(sim, 0.01); }).find("is 2e+03 particle spacings"), std::string::npos);
  // Refused before any walk (microseconds); the walk would take hours. 1 s allows a loaded machine.
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(1));
  sim.set_kernel_radius(0.005);  // half a spacing: no neighbours
  EXPECT_NE(error_of([&] { lattice(sim, 0.01); }).find("below one spacing a particle has no neighbours"),
            std::string::npos);
  EXPECT_EQ(sim.particles().size(), 0u);
  // h changed after the particles were made is checked against them.
  sim.set_kernel_radius(0.02);
  lattice(sim, 0.01);
  EXPECT_NE(error_of([&] { sim.set_kernel_radius(0.5); }).find("pbf.kernel_radius: the kernel radius h = 0.5 m is 50"),
            std::string::npos);
  EXPECT_EQ(sim.kernel_radius(), 0.02);
}

TEST(Limits, LatticesMustFitInMemoryAndHoldParticles) {
  Simulation sim;
  make_scene(sim, false);
  EXPECT_NE(error_of([&] { lattice(sim, 1e-6); }).find("1e+15 particles would need about"), std::string::npos);
  EXPECT_NE(error_of([&] { lattice(sim, 5e-324); }).find("too small"), std::string::npos);
  EXPECT_NE(error_of([&] { lattice(sim, 0.2); }).find("holds no lattice site"), std::string::npos);
  EXPECT_EQ(sim.particles().size(), 0u);
}

TEST(Limits, DomainsPositionsCannotResolveAreRefused) {
  for (double reach : {1e30, 1e308}) {
    Simulation sim;
    sim.set_domain(Domain{{0, 0, 0}, {reach, 1, 1}});
    sim.set_kernel_radius(0.02);
    sim.set_timestep(0.002);
    EXPECT_NE(error_of([&] { lattice(sim, 0.01); }).find("kernel radii (h = 0.02 m): more than 1e+06"),
              std::string::npos)
        << reach;
  }
  Simulation sim;
  EXPECT_NE(error_of([&] { sim.set_domain(Domain{{-1e308, 0, 0}, {1e308, 1, 1}}); }).find("hi must exceed lo"),
            std::string::npos);
}

TEST(Limits, AParticleThatOneStepCarriesAcrossTheDomainIsRefused) {
  Simulation sim;
  make_scene(sim, false);
  const double v[3] = {1e30, 0, 0};  // finite in single precision too
  lattice(sim, 0.01, v);
  sim.add_fix(StyleRegistry::builtin().make_fix("pbf", "pbf", {}));
  EXPECT_NE(error_of([&] { sim.run(1); }).find("farther than the whole domain (0.2 m) is wide"), std::string::npos);
  EXPECT_EQ(sim.step(), 0);
}

TEST(Limits, IdsMustBeNamesAndJobsUnique) {
  Simulation sim;
  make_scene(sim);
  const auto& registry = StyleRegistry::builtin();
  EXPECT_NE(error_of([&] { sim.add_fix(registry.make_fix("", "xsph", {})); }).find("must not be empty"),
            std::string::npos);
  EXPECT_NE(error_of([&] { sim.add_fix(registry.make_fix("a\nb", "xsph", {})); }).find("fix id 'a\\x0ab'"),
            std::string::npos);
  EXPECT_NE(error_of([&] { sim.add_compute(registry.make_compute("e.max", "speed", {})); }).find("compute id 'e.max'"),
            std::string::npos);
  EXPECT_NE(error_of([&] { sim.add_fix(registry.make_fix("pbf2", "pbf", {})); })
                .find("fix 'pbf2' (pbf): fix 'pbf' (pbf) does the time integration already"),
            std::string::npos);
  EXPECT_NE(error_of([&] { sim.add_fix(registry.make_fix("walls", "box", {})); }).find("walls at the domain faces"),
            std::string::npos);
  EXPECT_EQ(sim.fixes().size(), 3u);
}
