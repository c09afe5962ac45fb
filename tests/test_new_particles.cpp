// Particles added between runs (a lattice after pbf.run) start with every field a fix declares
// set by that fix (Fix::init_new_particles), not left at zero: for each pipeline with state
// (tests/pipelines.hpp), a block added after 10 steps, above the first one, must start as a
// fluid at rest does, and the run must go on. The fields at the next run's start:
//   - WCSPH's density: rest density with the continuity equation (an integrated density of 0
//     is a vacuum, and the pressure force tore the block apart within a step: NaN), the SPH
//     sum with the summation; the pressure the equation of state of that density;
//   - the integrator's acceleration: 0, as at a first start (leapfrog's documented first step);
//   - every other field finite.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "engine/core/simulation.hpp"
#include "engine/sph/lattice.hpp"
#include "pipelines.hpp"
#include "test_util.hpp"

using namespace pbf;
using namespace pbf::test;

class NewParticles : public ::testing::TestWithParam<const char*> {};

TEST_P(NewParticles, StartAsAFluidAtRestDoesAndTheRunGoesOn) {
  const auto dir = temp_dir("new-particles");
  const Pipeline p = pipeline(GetParam(), dir.path() / "out");
  Simulation sim;
  make_scene(sim, p.dt);
  add(sim, p);
  sim.run(10);
  const auto first_new = static_cast<std::int64_t>(sim.particles().next_id());
  const double lo[3] = {0.12, 0.02, 0.1}, hi[3] = {0.18, 0.08, 0.16}, rest[3] = {0, 0, 0};
  add_lattice(sim, lo, hi, 0.01, rest);
  sim.run(0);  // the start of a run: every fix's init, then the new particles' fields

  const Particles& P = sim.particles();
  const auto density = P.find("density"), pressure = P.find("pressure"), acceleration = P.find("acceleration");
  bool continuity = false;
  for (const auto& f : p.fixes)
    for (const auto& [name, value] : f.params)
      continuity = continuity || (f.style == "wcsph" && name == "density" && std::get<std::string>(value) == "continuity");
  const std::vector<real>& summed = sim.summed_density();
  int added = 0;
  for (std::size_t i = 0; i < P.size(); ++i) {
    if (P.ids()[i] < first_new) continue;
    ++added;
    const std::string what = "particle " + std::to_string(P.ids()[i]);
    for (FieldId f : P.fields())
      for (int c = 0; c < P.spec(f).components; ++c)
        ASSERT_TRUE(std::isfinite(P.data(f, c)[i])) << what << ": field '" << P.spec(f).name << "'";
    if (density) {
      const real expected = continuity ? real(sim.rest_density()) : summed[i];
      ASSERT_EQ(P.data(*density)[i], expected) << what << ": its density";
      ASSERT_GE(P.data(*pressure)[i], 0) << what;
    }
    if (acceleration)
      for (int c = 0; c < 3; ++c) ASSERT_EQ(P.data(*acceleration, c)[i], 0) << what;
  }
  EXPECT_EQ(added, 6 * 6 * 6);
  // The block falls 0.1 m onto the first one: the run goes on (a NaN or a density error stops it).
  ASSERT_NO_THROW(sim.run(20));
}

INSTANTIATE_TEST_SUITE_P(Pipelines, NewParticles,
                         ::testing::ValuesIn(kPipelines),
                         [](const auto& info) { return std::string(info.param); });
