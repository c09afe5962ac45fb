// Restarts carry everything a step hands to the next, for every pipeline that keeps such
// state: each pipeline below runs N steps straight, and separately N/2 steps, a restart, a
// fresh simulation that reads it and declares the same pipeline, and N/2 more. The two runs
// must end with byte-identical restart files and with every particle field, saved or not,
// equal bit for bit. The state at stake: PBF with vorticity and XSPH keeps none beyond
// positions and velocities; WCSPH keeps the leapfrog's accelerations, the continuity density
// and the CFL time step; then a solid in the fluid's way, a moving solid's pose in time, and
// the sample fix's file and the restart fix's list of files (in their saved states).
//
// N = 30 with the restart at step 15: the run loop reorders memory at step 20 (a multiple of
// 20), after the restart, so the continued run must reorder as the straight one does.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "engine/core/simulation.hpp"
#include "engine/io/restart.hpp"
#include "pipelines.hpp"
#include "test_util.hpp"

using namespace pbf;
using namespace pbf::test;

namespace {

constexpr int kSteps = 30;

}  // namespace

class Continued : public ::testing::TestWithParam<const char*> {};

TEST_P(Continued, EndsBitForBitAsTheStraightRun) {
  const auto dir = temp_dir("restart-pipelines");
  const auto out = dir / "out";
  const Pipeline p = pipeline(GetParam(), out);

  Simulation straight;
  make_scene(straight, p.dt);
  add(straight, p);
  straight.run(kSteps);
  write_restart(straight, (dir / "straight.restart").string());
  const std::string samples = read_file(out / "s.csv");  // empty without a sample fix
  // The continued run writes its outputs to the same paths (the fixes save them in their
  // states): a clean directory, as the straight run had.
  std::filesystem::remove_all(out);

  Simulation first;
  make_scene(first, p.dt);
  add(first, p);
  first.run(kSteps / 2);
  write_restart(first, (dir / "half.restart").string());
  Simulation continued;
  read_restart(continued, (dir / "half.restart").string());
  add(continued, p);
  continued.run(kSteps / 2);
  write_restart(continued, (dir / "continued.restart").string());

  ASSERT_EQ(continued.step(), kSteps);
  const std::string a = read_file(dir / "straight.restart"), b = read_file(dir / "continued.restart");
  // Each particle left: its id, position, velocity and mass.
  ASSERT_GT(straight.global_count(), 0u);
  ASSERT_GT(a.size(), straight.global_count() * (8 + 7 * sizeof(real)));
  EXPECT_TRUE(a == b) << "the restart files differ";
  expect_same_fields(straight.particles(), continued.particles());
  EXPECT_EQ(read_file(out / "s.csv"), samples);
  const bool sampled = std::any_of(p.fixes.begin(), p.fixes.end(), [](const auto& f) { return f.style == "sample"; });
  if (sampled)  // rows at t = 0 and every 2 steps
    EXPECT_EQ(pbf::test::read_csv(out / "s.csv").at("time").size(), 1u + kSteps / 2);
}

INSTANTIATE_TEST_SUITE_P(RestartPipelines, Continued,
                         ::testing::ValuesIn(kPipelines),
                         [](const auto& info) { return std::string(info.param); });
