// The test runner: GoogleTest, with the engine's info log (thermo, timing tables) silenced.
// In-process tests run on one OpenMP thread unless they ask for more (the thread tests set
// their counts). Threads wait as pbfengine's do, spinning briefly and then sleeping
// (engine/core/threads.hpp), so that ctest can run two test processes at once on two cores;
// ctest sets GOMP_SPINCOUNT itself (tests/CMakeLists.txt), which spares each process the
// restart. The scenario tests run the pbfengine binary with its own default (one thread per
// core this process may use).
#include <gtest/gtest.h>
#include <omp.h>
#include <spdlog/spdlog.h>

#include "engine/core/threads.hpp"

int main(int argc, char** argv) {
  pbf::restart_with_polite_waiting(argv);
  spdlog::set_level(spdlog::level::warn);
  omp_set_num_threads(1);
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
