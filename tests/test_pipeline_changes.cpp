// Changing the pipeline between runs: switching solvers (pbf to wcsph and back) and removing
// each fix in turn. A field's id must stay valid when other fields are freed, so the
// continued run must be exactly the run a fresh simulation makes from a restart of the same
// state with the new pipeline (restarts carry every field and fix state a step needs).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <tuple>
#include <vector>

#include "engine/core/error.hpp"
#include "engine/core/simulation.hpp"
#include "engine/io/restart.hpp"
#include "engine/registry/style_registry.hpp"
#include "engine/sph/lattice.hpp"
#include "test_util.hpp"

using namespace pbf;

namespace {

struct FixSpec {
  std::string id, style;
  GivenParams params;
};
using Pipeline = std::vector<FixSpec>;

const Pipeline kPbf = {{"gravity", "gravity", {}},
                       {"pbf", "pbf", {}},
                       {"vorticity", "vorticity", {}},
                       {"xsph", "xsph", {}},
                       {"walls", "box", {}}};
const Pipeline kWcsph = {{"gravity", "gravity", {}},
                         {"integrator", "leapfrog", {}},
                         {"wcsph", "wcsph", {{"density", std::string("continuity")}}},
                         {"viscosity", "sph_viscosity", {}},
                         {"cfl", "cfl", {}},
                         {"walls", "box", {}}};

// 1000 particles at spacing 0.01 m, h = 2 spacings, in a box twice as wide, falling.
void make_scene(Simulation& sim) {
  sim.set_domain(Domain{{0, 0, 0}, {0.2, 0.2, 0.3}});
  sim.set_kernel_radius(0.02);
  sim.set_timestep(0.002);
  const double lo[3] = {0, 0, 0.05}, hi[3] = {0.1, 0.1, 0.15}, v[3] = {0.1, 0, 0};
  add_lattice(sim, lo, hi, 0.01, v);
}

void add(Simulation& sim, const Pipeline& pipeline) {
  for (const auto& f : pipeline) sim.add_fix(StyleRegistry::builtin().make_fix(f.id, f.style, f.params));
}

Pipeline without(const Pipeline& pipeline, const std::string& id) {
  Pipeline out;
  for (const auto& f : pipeline)
    if (f.id != id) out.push_back(f);
  return out;
}

// Positions and velocities in id order.
std::vector<real> state(const Simulation& sim) {
  const auto& P = sim.particles();
  const auto index = P.index_of_id();
  std::vector<real> out;
  for (std::size_t id = 0; id < P.size(); ++id) {
    const std::size_t i = index[id];
    for (const real* a : {P.x(), P.y(), P.z(), P.vx(), P.vy(), P.vz()}) out.push_back(a[i]);
  }
  return out;
}

// Runs `steps`, or returns the error the run stops with.
std::string run(Simulation& sim, int steps) {
  try {
    sim.run(steps);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// The simulation `changed` goes on with `next` after the pipeline it ran with; `fresh` reads
// a restart of the same moment and declares `next` from scratch. Both run `steps`.
void expect_same_continuation(Simulation& changed, const Pipeline& next, const std::filesystem::path& restart,
                              int steps, const std::string& what) {
  Simulation fresh;
  read_restart(fresh, restart.string());
  add(fresh, next);
  const std::string changed_error = run(changed, steps), fresh_error = run(fresh, steps);
  EXPECT_EQ(changed_error, fresh_error) << what;
  if (!changed_error.empty()) return;
  const auto a = state(changed), b = state(fresh);
  ASSERT_EQ(a.size(), b.size()) << what;
  for (std::size_t k = 0; k < a.size(); ++k) {
    ASSERT_TRUE(std::isfinite(a[k])) << what << ": value " << k;
    ASSERT_EQ(a[k], b[k]) << what << ": particle " << k / 6 << ", value " << k % 6;
  }
}

}  // namespace

TEST(PipelineChanges, SwitchingSolversKeepsEveryFieldValid) {
  const auto dir = test::temp_dir("switch");
  Simulation sim;
  make_scene(sim);
  add(sim, kPbf);
  ASSERT_EQ(run(sim, 5), "");

  // pbf -> wcsph (the crash this test was written for: the leapfrog's field id pointed past
  // the end once pbf's lambda was freed).
  write_restart(sim, (dir / "to_wcsph.restart").string());
  for (const auto& f : kPbf) sim.remove_fix(f.id);
  add(sim, kWcsph);
  expect_same_continuation(sim, kWcsph, dir / "to_wcsph.restart", 20, "pbf to wcsph");
  EXPECT_FALSE(sim.particles().find("lambda"));
  EXPECT_FALSE(sim.particles().find("vorticity"));
  EXPECT_TRUE(sim.particles().find("acceleration"));

  // wcsph -> pbf.
  write_restart(sim, (dir / "to_pbf.restart").string());
  for (const auto& f : kWcsph) sim.remove_fix(f.id);
  add(sim, kPbf);
  expect_same_continuation(sim, kPbf, dir / "to_pbf.restart", 5, "wcsph to pbf");
  for (const char* gone : {"acceleration", "pressure", "density"}) EXPECT_FALSE(sim.particles().find(gone)) << gone;
  EXPECT_TRUE(sim.particles().find("lambda"));
}

TEST(PipelineChanges, RemovingAnyOneFixContinuesLikeAFreshPipeline) {
  const auto dir = test::temp_dir("remove");
  for (const Pipeline* pipeline : {&kPbf, &kWcsph}) {
    for (const auto& removed : *pipeline) {
      const std::string what = "removing '" + removed.id + "' from the " + (*pipeline)[1].style + " pipeline";
      Simulation sim;
      make_scene(sim);
      add(sim, *pipeline);
      ASSERT_EQ(run(sim, 5), "") << what;
      const auto restart = dir / (removed.id + ".restart");
      write_restart(sim, restart.string());
      sim.remove_fix(removed.id);
      expect_same_continuation(sim, without(*pipeline, removed.id), restart, 5, what);
    }
  }
}

// Without an integrator of accelerations the WCSPH forces go nowhere: the run is refused,
// naming the fix, rather than run silently without pressure.
TEST(PipelineChanges, RemovingTheLeapfrogUnderWcsphIsAnError) {
  Simulation sim;
  make_scene(sim);
  add(sim, kWcsph);
  ASSERT_EQ(run(sim, 2), "");
  sim.remove_fix("integrator");
  EXPECT_NE(run(sim, 2).find("fix 'wcsph' (wcsph): wcsph adds accelerations, but no fix integrates them"),
            std::string::npos);
}
