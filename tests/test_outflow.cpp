// Particles that leave: the outflow fix removes, at the start of each step, exactly the
// particles its region holds then; pbf.delete removes a region's particles between runs. The
// others keep their ids (an id names one particle for the scene's whole life), the flow
// compute counts and weighs what left, and the mass balance initial = present + removed holds.
#include <gtest/gtest.h>

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>

#include "engine/core/error.hpp"
#include "engine/core/parallel.hpp"
#include "engine/core/simulation.hpp"
#include "engine/io/restart.hpp"
#include "engine/registry/style_registry.hpp"
#include "pipelines.hpp"
#include "test_util.hpp"

using namespace pbf;
using namespace pbf::test;

namespace {

// The exact mass of the particles present (rounded once).
double mass_present(const Simulation& sim) {
  const auto& P = sim.particles();
  return deterministic_sum(P.size(), [&](std::size_t i) { return double(P.mass()[i]); });
}

std::map<std::int64_t, std::array<real, 3>> positions_by_id(const Simulation& sim) {
  const auto& P = sim.particles();
  std::map<std::int64_t, std::array<real, 3>> at;
  for (std::size_t i = 0; i < P.size(); ++i) at[P.ids()[i]] = {P.x()[i], P.y()[i], P.z()[i]};
  return at;
}

double flow_value(Simulation& sim, const std::string& compute, std::size_t k) {
  std::vector<double> v;
  sim.find_compute(compute)->evaluate(sim, v);
  return v.at(k);
}

}  // namespace

// The PBF block runs into a sink beyond x = 0.1 m. Step after step: the particles removed are
// exactly those beyond the plane after the step before (the exchange stage comes first), the
// others keep their ids, and what the flow compute counts is what left, in number and mass.
TEST(Outflow, RemovesAtEachStepsStartWhatItsRegionHoldsAndNothingElse) {
  const auto dir = temp_dir("outflow");
  const Pipeline p = pipeline("PbfOutflow", dir.path() / "out");
  Simulation sim;
  make_scene(sim, p.dt);
  add(sim, p);
  const double initial_mass = mass_present(sim);
  const std::size_t initial = sim.particles().size();
  std::size_t removed_total = 0;
  for (int step = 0; step < 30; ++step) {
    const auto before = positions_by_id(sim);
    sim.run(1);
    const auto after = positions_by_id(sim);
    std::size_t beyond = 0;
    for (const auto& [id, x] : before) {
      const bool in_region = x[0] > real(0.1);
      beyond += in_region;
      ASSERT_EQ(after.count(id), in_region ? 0u : 1u) << "particle " << id << " at x = " << x[0] << ", step " << step;
    }
    ASSERT_EQ(after.size(), before.size() - beyond);
    removed_total += beyond;
  }
  EXPECT_GT(removed_total, 100u);  // at 0.5 m/s for 0.06 s, the block's front 3 cm at least
  EXPECT_EQ(flow_value(sim, "out", 0), static_cast<double>(removed_total));
  EXPECT_EQ(sim.particles().size() + removed_total, initial);
  // initial = present + removed: three sums, each exact then rounded once, so they agree to
  // the rounding of the largest, 2^-53 of the initial mass, three times over.
  EXPECT_NEAR(mass_present(sim) + flow_value(sim, "out", 1), initial_mass, 3 * 0x1p-53 * initial_mass);
}

// Which thread removes what changes no bit: the same particles, ids and fields at 1 and 2 threads.
TEST(Outflow, TheSameBitsAtOneAndTwoThreads) {
  for (const char* name : {"PbfOutflow", "WcsphOutflow", "PbfEmitter", "WcsphEmitter"}) {
    const auto dir = temp_dir("outflow-threads");
    const Pipeline p = pipeline(name, dir.path() / "out");
    Simulation one, two;
    for (auto [sim, threads] : {std::pair{&one, 1}, std::pair{&two, 2}}) {
      omp_set_num_threads(threads);
      make_scene(*sim, p.dt);
      add(*sim, p);
      sim->run(40);
    }
    omp_set_num_threads(1);
    SCOPED_TRACE(name);
    EXPECT_TRUE(one.particles().size() < 800u || one.particles().next_id() > 800) << "no particle came or went";
    expect_same_fields(one.particles(), two.particles());
  }
}

// A fix may change the particle set only in its exchange hook; anywhere else the run stops
// with a message that says where it may.
TEST(Outflow, ChangingTheParticlesOutsideTheExchangeStageIsRefused) {
  class AddsInPredict : public Fix {
   public:
    AddsInPredict() : Fix("adder", "test") {}
    std::vector<Stage> stages() const override { return {Stage::external_forces}; }
    void external_forces(Simulation& sim) override {
      const real x[3] = {0.15, 0.05, 0.1}, v[3] = {0, 0, 0};
      sim.particles().add(x, v, sim.particles().mass()[0]);
    }
  };
  const auto dir = temp_dir("outflow-frozen");
  const Pipeline p = pipeline("PbfVorticityXsph", dir.path() / "out");
  Simulation sim;
  make_scene(sim, p.dt);
  add(sim, p);
  sim.add_fix(std::make_unique<AddsInPredict>());
  EXPECT_ERROR_NAMING(sim.run(1), "fix 'adder'", "only a fix's exchange hook (the step's start) may add or remove");
  // Between runs a script may (pbf.lattice, pbf.delete).
  const real x[3] = {0.15, 0.05, 0.1}, v[3] = {0, 0, 0};
  EXPECT_NO_THROW(sim.particles().add(x, v, real(0.001)));
}

// pbf.delete, each region: it returns how many it removed, the lattice sites inside (counted
// here from the sites' coordinates), and the others keep their ids, which are the site numbers.
TEST(Delete, RemovesTheParticlesInsideARegionAndKeepsTheOthersIds) {
  const auto dir = temp_dir("delete");
  // A 10^3 lattice of spacing 0.01 m from the origin: site k at 0.005 + 0.01 (k % 10, k / 10 % 10, k / 100).
  const std::string scene =
      "pbf.domain{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.1}}; pbf.kernel_radius(0.02); pbf.timestep(0.001)\n"
      "pbf.lattice{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.1}, spacing = 0.01}\n"
      "local n = pbf.delete{region = 'box', lo = {0, 0, 0}, hi = {0.1, 0.1, 0.031}}\n"
      "local m = pbf.delete{region = 'sphere', center = {0.05, 0.05, 0.07}, radius = 0.0201}\n"
      "local k = pbf.delete{region = 'half_space', point = {0.0801, 0, 0}, normal = {2, 0, 0}}\n"
      "print(string.format('removed %d %d %d left %d', n, m, k, pbf.count()))\n"
      "pbf.compute('rho', 'density', {})\n"
      "local ids = {} for id in pairs(pbf.value('rho')) do ids[#ids + 1] = id - 1 end table.sort(ids)\n"
      "print('ids ' .. table.concat(ids, ' '))\n";
  write_file(dir / "d.lua", scene);
  const auto r = run_engine("run " + (dir / "d.lua").string());
  ASSERT_EQ(r.code, 0) << r.output;
  // The box holds the layers z = 0.005, 0.015, 0.025: 300 sites. The sphere about (0.05, 0.05,
  // 0.07) of radius 0.0201 holds the sites within two spacings on the lattice: offsets of
  // +-0.005 or +-0.015 per axis with a squared length up to 4.04e-4, counted below; the
  // half-space x > 0.0801 the columns x = 0.085, 0.095 of what is left.
  std::set<int> left;
  int in_sphere = 0, beyond = 0;
  for (int k = 0; k < 1000; ++k) {
    const double x = 0.005 + 0.01 * (k % 10), y = 0.005 + 0.01 * (k / 10 % 10), z = 0.005 + 0.01 * (k / 100);
    if (z < 0.031) continue;
    if (std::hypot(x - 0.05, y - 0.05, z - 0.07) <= 0.0201) {
      ++in_sphere;
      continue;
    }
    if (x > 0.0801) {
      ++beyond;
      continue;
    }
    left.insert(k);
  }
  EXPECT_NE(r.output.find("removed 300 " + std::to_string(in_sphere) + " " + std::to_string(beyond) + " left " +
                          std::to_string(left.size())),
            std::string::npos)
      << r.output;
  std::string ids = "ids";
  for (int k : left) ids += " " + std::to_string(k);
  EXPECT_NE(r.output.find(ids + "\n"), std::string::npos) << r.output;
}

// A region that is not one, said with the parameter it concerns.
TEST(Delete, ABadRegionIsAClearError) {
  const auto dir = temp_dir("delete-bad");
  const std::string scene =
      "pbf.domain{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.1}}; pbf.kernel_radius(0.02); pbf.timestep(0.001)\n"
      "pbf.lattice{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.1}, spacing = 0.01}\n";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"pbf.delete{region = 'cube', lo = {0, 0, 0}, hi = {1, 1, 1}}", "got \"cube\""},
      {"pbf.delete{region = 'box', lo = {0, 0, 0}}", "parameter 'hi' is missing: region \"box\" needs lo and hi"},
      {"pbf.delete{region = 'sphere', center = {0, 0, 0}, radius = 0.1, lo = {0, 0, 0}}",
       "parameter 'lo' does not apply to region \"sphere\""},
      {"pbf.delete{region = 'box', lo = {0, 0, 0}, hi = {0.1, 0, 0.1}}", "the box is empty along y"},
      {"pbf.delete{region = 'half_space', point = {0, 0, 0}, normal = {0, 0, 0}}", "parameter 'normal' is the zero vector"},
      {"pbf.delete{region = 'solid', solid = 'ball'}", "parameter 'solid': no solid 'ball' in the pipeline"},
      {"pbf.delete{region = 'sphere', center = {0, 0, 0}, radius = -1}", "radius"},
  };
  for (const auto& [call, expected] : cases) {
    write_file(dir / "d.lua", scene + call + "\n");
    const auto r = run_engine("run " + (dir / "d.lua").string());
    EXPECT_EQ(r.code, 1) << call;
    EXPECT_NE(r.output.find("d.lua:3:"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(expected), std::string::npos) << call << "\n" << r.output;
  }
}

// The flow compute names what it cannot read.
TEST(Flow, NamesAFixThatIsMissingOrPassesNoParticles) {
  const auto dir = temp_dir("flow");
  const Pipeline p = pipeline("PbfOutflow", dir.path() / "out");
  Simulation sim;
  make_scene(sim, p.dt);
  add(sim, p);
  const auto& styles = StyleRegistry::builtin();
  sim.add_compute(styles.make_compute("a", "flow", {{"fix", std::string("drian")}}));
  sim.add_compute(styles.make_compute("b", "flow", {{"fix", std::string("pbf")}}));
  std::vector<double> v;
  EXPECT_ERROR_NAMING(sim.find_compute("a")->evaluate(sim, v), "no fix 'drian'", "did you mean 'drain'");
  EXPECT_ERROR_NAMING(sim.find_compute("b")->evaluate(sim, v), "fix 'pbf' (pbf)", "adds and removes no particles");
  sim.find_compute("out")->evaluate(sim, v);
  EXPECT_EQ(v, (std::vector<double>{0, 0}));
}

// A scene drained of every particle runs on (computes of the particles say NaN where there is
// nothing to measure), and its restart, with no particle, reads back with the next id.
TEST(Outflow, ADrainedSceneRunsOnAndItsRestartReadsBack) {
  const auto dir = temp_dir("outflow-drained");
  Pipeline p = pipeline("PbfOutflow", dir.path() / "out");
  p.fixes.back().params = {{"region", std::string("box")}, {"lo", Vec3{0, 0, 0}}, {"hi", Vec3{0.2, 0.1, 0.2}}};
  p.computes.push_back({"front", "front", {}});
  Simulation sim;
  make_scene(sim, p.dt);
  add(sim, p);
  sim.run(2);
  EXPECT_EQ(sim.global_count(), 0u);
  EXPECT_EQ(flow_value(sim, "out", 0), 800.0);
  EXPECT_TRUE(std::isnan(flow_value(sim, "front", 0)));
  ASSERT_NO_THROW(sim.run(3));
  EXPECT_EQ(sim.step(), 5);
  write_restart(sim, (dir / "empty.restart").string());
  Simulation back;
  read_restart(back, (dir / "empty.restart").string());
  EXPECT_EQ(back.global_count(), 0u);
  EXPECT_EQ(back.particles().next_id(), 800);
}

// A box with an open face: the block moving at 0.5 m/s along x leaves through x+ (no wall
// holds it back, none counts in its density), the particles beyond it leave the run at the
// next step's start, and initial = present + left holds; the other faces stay walls.
TEST(OpenFace, TheFluidLeavesThroughItAndTheOthersStayWalls) {
  const auto dir = temp_dir("open-face");
  Pipeline p = pipeline("PbfVorticityXsph", dir.path() / "out");
  for (auto& f : p.fixes)
    if (f.style == "box") f.params = {{"open", Names{"x+"}}};
  p.computes.push_back({"left", "flow", {{"fix", std::string("walls")}}});
  Simulation sim;
  make_scene(sim, p.dt);
  add(sim, p);
  const double initial_mass = mass_present(sim);
  std::size_t beyond_before = 0;
  for (int step = 0; step < 150; ++step) {
    const auto before = positions_by_id(sim);
    sim.run(1);
    const auto after = positions_by_id(sim);
    for (const auto& [id, x] : before)  // beyond the face after a step: gone after the next
      ASSERT_EQ(after.count(id), x[0] > real(0.2) ? 0u : 1u) << "particle " << id << ", step " << step;
    for (const auto& [id, x] : after) {
      beyond_before += x[0] > real(0.2);
      ASSERT_GE(x[2], real(0.005) - real(1e-6)) << "the floor holds";  // the contact distance, half a spacing
      ASSERT_GE(x[0], real(0.005) - real(1e-6)) << "the back wall holds";
    }
  }
  EXPECT_GT(beyond_before, 100u);
  const double left = flow_value(sim, "left", 0);
  EXPECT_EQ(sim.particles().size() + static_cast<std::size_t>(left), 800u);
  EXPECT_NEAR(mass_present(sim) + flow_value(sim, "left", 1), initial_mass, 3 * 0x1p-53 * initial_mass);
}

TEST(OpenFace, AFaceNamedTwiceOrOnAPeriodicAxisIsRefused) {
  const auto& styles = StyleRegistry::builtin();
  EXPECT_ERROR_NAMING(styles.make_fix("walls", "box", {{"open", Names{"x+", "x+"}}}), "parameter 'open'", "twice");
  EXPECT_ERROR_NAMING(styles.make_fix("walls", "box", {{"open", Names{"w+"}}}), "'open'", "\"w+\"");
  Simulation sim;
  Domain d{{0, 0, 0}, {0.2, 0.1, 0.2}};
  d.periodic[1] = true;
  sim.set_domain(d);
  sim.set_kernel_radius(0.02);
  sim.set_timestep(0.002);
  const double lo[3] = {0, 0, 0}, hi[3] = {0.1, 0.1, 0.08}, v[3] = {0, 0, 0};
  add_lattice(sim, lo, hi, 0.01, v);
  sim.add_fix(styles.make_fix("pbf", "pbf", {}));
  sim.add_fix(styles.make_fix("walls", "box", {{"open", Names{"y-"}}}));
  EXPECT_ERROR_NAMING(sim.run(1), "parameter 'open'", "axis y is periodic");
}
