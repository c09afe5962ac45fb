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

// Counts allocations from the end of step `from` to the end of step `to`.
class AllocationWatch : public Fix {
 public:
  AllocationWatch(std::int64_t from, std::int64_t to) : Fix("watch", "allocation watch"), from_(from), to_(to) {}
  std::vector<Stage> stages() const override { return {Stage::end_of_step}; }
  Role role() const override { return Role::output; }
  void end_of_step(Simulation& sim) override {
    if (sim.step() == from_) counting = true;
    if (sim.step() == to_) counting = false;
  }

 private:
  std::int64_t from_, to_;
};

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
  Domain d;
  d.hi[0] = d.hi[1] = d.hi[2] = 0.4;
  sim.set_domain(d);
  const double s = 0.01;
  sim.set_kernel_radius(2 * s);
  sim.set_timestep(0.002);
  const double lo[3] = {s / 2, s / 2, s / 2}, hi[3] = {0.1, 0.4 - s / 2, 0.2}, v[3] = {0, 0, 0};
  add_lattice(sim, lo, hi, s, v);
  sim.add_fix(styles().make_fix("gravity", "gravity", {{"acceleration", std::array<double, 3>{0, 0, -9.81}}}));
  sim.add_fix(styles().make_fix("pbf", "pbf", {}));
  sim.add_fix(styles().make_fix("vorticity", "vorticity", {}));
  sim.add_fix(styles().make_fix("xsph", "xsph", {}));
  sim.add_fix(styles().make_fix("walls", "box", {}));
  sim.add_fix(std::make_unique<AllocationWatch>(10, 40));  // across a reordering (every 20 steps)
  allocations = 0;
  sim.run(40);
  omp_set_num_threads(1);
  EXPECT_EQ(allocations.load(), 0) << "allocations in steps 11 to 40 of " << sim.particles().size() << " particles";
}

}  // namespace
