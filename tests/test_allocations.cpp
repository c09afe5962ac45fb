// After the first steps a run allocates no memory: every buffer keeps its capacity from one
// step to the next, and those that grow grow geometrically (issue 11). Counted by replacing
// the global operator new of this test binary (every std::vector and std::string allocates
// through it); the count is on only while the watched steps run.
#include <gtest/gtest.h>

#include <array>
#include <atomic>
#include <cstdlib>
#include <new>
#include <vector>
#include <omp.h>

#include "engine/core/simulation.hpp"
#include "engine/registry/style_registry.hpp"
#include "engine/sph/lattice.hpp"
#include "step_window.hpp"

namespace {
std::atomic<bool> counting{false};
std::atomic<long> allocations{0};
}  // namespace

void* operator new(std::size_t size) {
  if (counting.load(std::memory_order_relaxed)) allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size ? size : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace {

using namespace pbf;

const StyleRegistry& styles() { return StyleRegistry::builtin(); }

TEST(Allocations, NoneAfterTheFirstTenStepsOfTheDamBreak) {
  // The counter sees a vector's allocation (else the test below could not fail).
  counting = true;
  auto* probe = new std::vector<int>(8);
  counting = false;
  EXPECT_EQ(allocations.load(), 2);  // the vector and its array
  delete probe;

  omp_set_num_threads(2);
  Simulation sim;
  test::small_dam_break(sim);
  sim.add_fix(styles().make_fix("gravity", "gravity", {{"acceleration", std::array<double, 3>{0, 0, -9.81}}}));
  sim.add_fix(styles().make_fix("pbf", "pbf", {}));
  sim.add_fix(styles().make_fix("vorticity", "vorticity", {}));
  sim.add_fix(styles().make_fix("xsph", "xsph", {}));
  sim.add_fix(styles().make_fix("walls", "box", {}));
  // Steps 11 to 40: across a reordering (every 20 steps).
  sim.add_fix(std::make_unique<test::StepWindow>(counting, 10, 40));
  allocations = 0;
  sim.run(40);
  omp_set_num_threads(1);
  EXPECT_EQ(allocations.load(), 0) << "allocations in steps 11 to 40 of " << sim.particles().size() << " particles";
}

// Fluid that comes and goes allocates no more than a closed box: a jet into a drain, watched
// once the count has settled (the jet reaches the drain at about 0.2 s), each step emitting
// and removing, across a reordering. The arrays keep the capacity the run's largest count
// gave them; a count above it would grow them geometrically, rarely, and the settled jet's
// count stays within a few percent of its level.
TEST(Allocations, NoneInStepsThatEmitAndRemove) {
  omp_set_num_threads(2);
  Simulation sim;
  sim.set_domain(Domain{{0, 0, 0}, {0.2, 0.2, 0.3}});
  sim.set_kernel_radius(0.02);
  sim.set_timestep(0.001);
  sim.add_fix(styles().make_fix("gravity", "gravity", {}));
  sim.add_fix(styles().make_fix("pbf", "pbf", {}));
  sim.add_fix(styles().make_fix("walls", "box", {}));
  sim.add_fix(styles().make_fix("jet", "emitter",
                                {{"shape", std::string("disc")}, {"center", Vec3{0.1, 0.1, 0.25}},
                                 {"normal", Vec3{0, 0, -1}}, {"radius", 0.02}, {"speed", 1.0}, {"spacing", 0.01}}));
  sim.add_fix(styles().make_fix("drain", "outflow",
                                {{"region", std::string("box")}, {"lo", Vec3{0, 0, 0}}, {"hi", Vec3{0.2, 0.2, 0.02}}}));
  sim.add_fix(std::make_unique<test::StepWindow>(counting, 600, 700));
  allocations = 0;
  sim.run(700);
  omp_set_num_threads(1);
  EXPECT_GT(sim.particles().next_id(), 2 * static_cast<std::int64_t>(sim.particles().size()));  // emitted and removed
  EXPECT_EQ(allocations.load(), 0) << "allocations in steps 601 to 700 of about " << sim.particles().size()
                                   << " particles";
}

}  // namespace
