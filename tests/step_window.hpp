#pragma once
// What tests that count something over a window of steps share (allocations, parallel
// regions): a fix that turns a flag on and off at the ends of two steps, and a small dam break.
#include <atomic>
#include <cstdint>
#include <vector>

#include "engine/core/simulation.hpp"
#include "engine/sph/lattice.hpp"

namespace pbf::test {

// Turns `flag` on at the end of step `from` and off at the end of step `to`; an output, so
// the last of its stage.
class StepWindow : public Fix {
 public:
  StepWindow(std::atomic<bool>& flag, std::int64_t from, std::int64_t to)
      : Fix("window", "step window"), flag_(flag), from_(from), to_(to) {}
  std::vector<Stage> stages() const override { return {Stage::end_of_step}; }
  Role role() const override { return Role::output; }
  void end_of_step(Simulation& sim) override {
    if (sim.step() == from_) flag_ = true;
    if (sim.step() == to_) flag_ = false;
  }

 private:
  std::atomic<bool>& flag_;
  std::int64_t from_, to_;
};

// A column 0.1 m wide and 0.2 m high against the x = 0 wall of a 0.4 m box (3,200
// particles at a spacing of 0.01 m, h = 2 spacings, dt = 2 ms), no fixes yet.
inline void small_dam_break(Simulation& sim) {
  Domain d;
  d.hi[0] = d.hi[1] = d.hi[2] = 0.4;
  sim.set_domain(d);
  const double s = 0.01;
  sim.set_kernel_radius(2 * s);
  sim.set_timestep(0.002);
  const double lo[3] = {s / 2, s / 2, s / 2}, hi[3] = {0.1, 0.4 - s / 2, 0.2}, v[3] = {0, 0, 0};
  add_lattice(sim, lo, hi, s, v);
}

}  // namespace pbf::test
