// The ghost-refresh check in one process (Simulation::set_check_ghosts): a distributed run's
// pair loops read other ranks' particles through ghosts, whose values a pass must refresh
// (update_ghosts) after it changes them and before it reads them at neighbours. A missed
// refresh shows under MPI only as different bits at some rank counts; the check makes it show
// in one process. Every particle gets a copy as a ghost and the lists name the copies, so
// every value read at a neighbour is a ghost's; the scratch arrays are NaN when a hook starts.
//
// What must hold:
// - every pipeline that reads values at neighbours ends with the plain run's bits (each pass
//   refreshes what it reads: the copies equal the originals when read);
// - a pass that forgets to refresh a scratch array it reads at neighbours stops the run at a
//   non-finite value; one that forgets a field it changed ends with other bits (the stale
//   copies): the check can fail, so it checks something.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <string>

#include "engine/core/error.hpp"
#include "engine/core/fix.hpp"
#include "engine/core/simulation.hpp"
#include "pipelines.hpp"
#include "test_util.hpp"

using namespace pbf;
using namespace pbf::test;

namespace {

constexpr int kSteps = 30;

// Nudges each velocity by a tiny multiple of a sum over the neighbours, after the solver set
// the velocities: of |v_j|^2 (a scratch array) or of v_j itself (a field it just changed).
// `refresh` says whether it calls update_ghosts as it must.
class NeighbourNudge : public Fix {
 public:
  enum class Reads { scratch, velocity };
  NeighbourNudge(Reads reads, bool refresh) : Fix("nudge", "nudge"), reads_(reads), refresh_(refresh) {}
  std::vector<Stage> stages() const override { return {Stage::velocity_post}; }
  bool needs_neighbors() const override { return true; }
  bool runs_distributed() const override { return true; }
  void velocity_post(Simulation& sim) override {
    auto& P = sim.particles();
    const std::size_t n = P.size();
    real *vx = P.vx(), *vy = P.vy();
    const NeighborGrid& grid = sim.neighbors();
    if (reads_ == Reads::scratch) {
      real* speed2 = sim.scratch(0);
      for (std::size_t i = 0; i < n; ++i) speed2[i] = vx[i] * vx[i] + vy[i] * vy[i];
      if (refresh_) sim.update_ghosts({speed2});
      for (std::size_t i = 0; i < n; ++i) {
        real sum = 0;
        grid.for_each_neighbor(i, P.x(), P.y(), P.z(), [&](std::uint32_t j, real, real, real, real) { sum += speed2[j]; });
        vx[i] += real(1e-4) * sum;
      }
      return;
    }
    // The velocities changed since the neighbour stage (the solver's velocity update): a
    // pass that reads them at neighbours refreshes them first. The new values go to a
    // scratch array, so every particle reads its neighbours' velocities of before.
    if (refresh_) sim.update_ghosts({vx, vy});
    real* next = sim.scratch(1);
    for (std::size_t i = 0; i < n; ++i) {
      real sum = 0;
      grid.for_each_neighbor(i, P.x(), P.y(), P.z(), [&](std::uint32_t j, real, real, real, real) { sum += vy[j]; });
      next[i] = vx[i] + real(1e-3) * sum;
    }
    std::copy(next, next + n, vx);
  }

 private:
  Reads reads_;
  bool refresh_;
};

// Runs `name`'s pipeline (plus `extra`, when given) for kSteps, checked or not.
std::unique_ptr<Simulation> run(const std::string& name, bool checked, std::unique_ptr<Fix> extra = nullptr) {
  static const auto dir = temp_dir("ghost-refresh");  // the sample fix's and restart fix's files
  const auto out = dir.path() / (checked ? "checked" : "plain");
  auto sim = std::make_unique<Simulation>();
  const Pipeline p = pipeline(name, out);
  make_scene(*sim, p.dt);
  add(*sim, p);
  if (extra) sim->add_fix(std::move(extra));
  sim->set_check_ghosts(checked);
  sim->run(kSteps);
  return sim;
}

}  // namespace

class GhostRefresh : public ::testing::TestWithParam<const char*> {};

TEST_P(GhostRefresh, TheCheckedRunEndsWithThePlainRunsBits) {
  const auto plain = run(GetParam(), false), checked = run(GetParam(), true);
  ASSERT_EQ(checked->step(), kSteps);
  expect_same_fields(plain->particles(), checked->particles());
}

INSTANTIATE_TEST_SUITE_P(Pipelines, GhostRefresh,
                         ::testing::ValuesIn(kPipelines),
                         [](const auto& info) { return std::string(info.param); });

using Reads = NeighbourNudge::Reads;

TEST(GhostCheck, AFixThatRefreshesWhatItReadsPasses) {
  for (Reads reads : {Reads::scratch, Reads::velocity}) {
    const auto plain = run("PbfVorticityXsph", false, std::make_unique<NeighbourNudge>(reads, true));
    const auto checked = run("PbfVorticityXsph", true, std::make_unique<NeighbourNudge>(reads, true));
    expect_same_fields(plain->particles(), checked->particles());
  }
}

TEST(GhostCheck, AMissedRefreshOfAScratchArrayStopsTheRun) {
  // In one process without the check the missing refresh changes nothing...
  const auto plain = run("PbfVorticityXsph", false, std::make_unique<NeighbourNudge>(Reads::scratch, false));
  ASSERT_EQ(plain->step(), kSteps);
  // ...with it, the neighbours' values are NaN, and the run stops at the first step's check.
  try {
    run("PbfVorticityXsph", true, std::make_unique<NeighbourNudge>(Reads::scratch, false));
    FAIL() << "the checked run went on";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("step 1"), std::string::npos) << e.what();
  }
}

TEST(GhostCheck, AMissedRefreshOfAChangedFieldChangesTheBits) {
  // A pipeline whose velocities are changed in place (XSPH's new ones come from a scratch
  // array, whose poisoned ghosts would stop the run instead).
  const auto plain = run("PbfSolid", false, std::make_unique<NeighbourNudge>(Reads::velocity, false));
  const auto checked = run("PbfSolid", true, std::make_unique<NeighbourNudge>(Reads::velocity, false));
  // The copies hold the velocities of the neighbour stage, not the solver's new ones.
  const Particles &a = plain->particles(), &b = checked->particles();
  ASSERT_EQ(a.size(), b.size());
  double most = 0;
  for (std::size_t i = 0; i < a.size(); ++i) most = std::max(most, std::fabs(double(a.vx()[i]) - double(b.vx()[i])));
  EXPECT_GT(most, 0.0) << "the stale copies went unnoticed";
}

// The command line's switch, on the MPI tests' dam break (tests/mpi/dambreak.lua: PBF with
// vorticity, XSPH, box walls and a solid block, and outputs that read neighbours: the dumped
// density and |omega|, probes, gauges, the solid's load): every file it writes is the same.
TEST(GhostCheck, TheCommandLinesSwitchGivesThePlainRunsFiles) {
  const auto dir = temp_dir("ghost-check-cli");
  const std::string script = std::string(PBF_SOURCE_DIR) + "/tests/mpi/dambreak.lua";
  for (const std::string run : {"plain", "checked"}) {
    const auto result = run_engine(std::string("run ") + (run == "checked" ? "--check-ghosts " : "") + script +
                                   " -v steps=60 -v out=" + (dir.path() / run).string());
    ASSERT_EQ(result.code, 0) << result.output;
  }
  int files = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir.path() / "plain")) {
    if (!entry.is_regular_file()) continue;
    const auto relative = std::filesystem::relative(entry.path(), dir.path() / "plain");
    EXPECT_EQ(read_file(entry.path()), read_file(dir.path() / "checked" / relative)) << relative;
    ++files;
  }
  EXPECT_GE(files, 6);  // two text frames, two VTK frames and their collection, probes, thermo
}
