#pragma once
// The benchmarks' scene: the PBF dam break of `share/make_scene.py --kind dambreak` (and
// scenarios/init_file.lua's pipeline), built in C++ through the public engine interfaces,
// run a few steps so the column is in motion, and kept per size for every benchmark of that
// size to share.
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "engine/core/fix.hpp"
#include "engine/core/real.hpp"
#include "engine/core/simulation.hpp"

namespace pbf::bench {

// make_scene.py's dam break in the domain [0, L]^3, L = 1: a column a = L/5 wide (x), 2a high
// (z), filling the whole depth L (y), against x = 0; lattice sites at (i + 1/2) s with
// s = a / k, so k x 5k x 2k = 10 k^3 particles, k chosen for the count closest to the target
// (the coarser lattice on a tie); h = 2 s; dt = min(0.002, 0.4 h / sqrt(2 g L)) rounded down to
// two significant digits (0.002 for the 8k and 32k scenes, 0.0015 for 128k).
struct DamBreakPlan {
  int k = 0;
  double L = 1, a = 0.2, spacing = 0, h = 0, dt = 0;
  std::size_t particles = 0;
};
DamBreakPlan plan_dam_break(std::size_t target);

class DamBreak {
 public:
  static constexpr int kWarmupSteps = 10;

  // Builds the scene (gravity, pbf with 4 iterations, vorticity, xsph, box walls: the styles'
  // defaults otherwise) and runs kWarmupSteps steps.
  explicit DamBreak(std::size_t target);

  Simulation& sim() { return *sim_; }
  const DamBreakPlan& plan() const { return plan_; }
  std::size_t size() const { return sim_->particles().size(); }
  // The fix of this id ("pbf", "vorticity", "xsph", "walls", "gravity").
  Fix& fix(const std::string& id) const;
  // Simulated time since the warm-up ended.
  double time_since_warmup() const { return sim_->time() - warm_time_; }

  // Positions and velocities as the warm-up left them, with neighbour lists built at those
  // positions and the summed density cached; benchmarks that move particles or change
  // velocities say so, and the next restore() puts back only what they changed.
  void restore();
  void positions_changed() { positions_dirty_ = true; }
  void velocities_changed() { velocities_dirty_ = true; }

 private:
  DamBreakPlan plan_;
  std::unique_ptr<Simulation> sim_;
  double warm_time_ = 0;
  std::vector<real> saved_[6];  // x, y, z, vx, vy, vz after the warm-up
  bool positions_dirty_ = true, velocities_dirty_ = false;
};

// Scenes shared across benchmarks, built on first use: one per size whose particles only the
// single-pass benchmarks touch (each restores it before timing), and one per size that the
// whole-step benchmark advances.
DamBreak& pass_scene(std::size_t target);
DamBreak& step_scene(std::size_t target);
// Builds the stepping scene of this size again from scratch (after ~0.5 s of simulated time).
DamBreak& rebuild_step_scene(std::size_t target);

}  // namespace pbf::bench
