// The test runner: GoogleTest, with the engine's info log (thermo, timing tables) silenced.
// In-process tests run on one OpenMP thread unless they ask for more (the thread tests set
// their counts): ctest runs two test processes at once on two cores, and oversubscribed
// OpenMP barriers would make tests of thousands of tiny runs crawl. The scenario tests run
// the pbfengine binary with its own default (all cores).
#include <gtest/gtest.h>
#include <omp.h>
#include <spdlog/spdlog.h>

int main(int argc, char** argv) {
  spdlog::set_level(spdlog::level::warn);
  omp_set_num_threads(1);
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
