#pragma once
// What the dam-break micro-benchmarks share (bench/micro.cpp, bench/pbf_passes.cpp): the
// fixture, the sizes, and the counters (bench/README.md). Counters of every pass:
//   items_per_second     particles per second (one pass over every particle per iteration)
//   particles            the scene's particle count (the argument N is the target count)
//   mean_neighbors       mean neighbour-list length of the lists the pass reads
//   flops_per_particle   the pass's flops per particle (bench/flops.hpp)
//   flops                flops_per_particle x particles/s
//   peak_fraction        flops over the FMA peak of one thread times the OpenMP threads
//                        (bench/main.cpp)
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "bench/scene.hpp"

namespace pbf::bench {

// The FMA peak of the engine's threads in its precision, flop/s (bench/main.cpp; 0: none).
extern double g_peak_flops;

// The real time of a benchmark's timed loop, for peak_fraction: a rate counter would be shown
// as "0.2/s", so the fraction is computed here (the loop's own overhead is negligible).
class LoopClock {
 public:
  double seconds() const { return std::chrono::duration<double>(Clock::now() - start_).count() - paused_; }
  // Time spent outside the timed work (state.PauseTiming) that seconds() leaves out.
  void pause() { pause_start_ = Clock::now(); }
  void resume() { paused_ += std::chrono::duration<double>(Clock::now() - pause_start_).count(); }

 private:
  using Clock = std::chrono::steady_clock;
  Clock::time_point start_ = Clock::now(), pause_start_;
  double paused_ = 0;
};

// The counters of a pass over `particles` particles per iteration (see the top), timed by
// `clock`; per_pair and per_particle are its flops (bench/flops.hpp; both 0: not counted).
inline void report(benchmark::State& state, const LoopClock& clock, std::size_t particles, double mean_neighbors,
                   double per_pair, double per_particle) {
  const double seconds = clock.seconds();
  const double n = static_cast<double>(particles), iterations = static_cast<double>(state.iterations());
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(particles));
  state.counters["particles"] = n;
  state.counters["mean_neighbors"] = mean_neighbors;
  if (per_pair <= 0 && per_particle <= 0) return;
  const double per = per_pair * mean_neighbors + per_particle;
  state.counters["flops_per_particle"] = per;
  state.counters["flops"] = benchmark::Counter(per * n * iterations, benchmark::Counter::kIsRate);
  if (g_peak_flops > 0 && seconds > 0) state.counters["peak_fraction"] = per * n * iterations / seconds / g_peak_flops;
}

// Whether every position and velocity is finite (a pass repeated hundreds of times on the
// same particles must not blow up; the benchmarks that change them check).
inline bool finite(const Simulation& sim) {
  const auto& P = sim.particles();
  const real* a[6] = {P.x(), P.y(), P.z(), P.vx(), P.vy(), P.vz()};
  for (const real* c : a)
    for (std::size_t i = 0; i < P.size(); ++i)
      if (!std::isfinite(c[i])) return false;
  return true;
}

// The fixture, named for the benchmarks' names (dambreak/PASS/N:SIZE): the shared scene of
// this size, as the warm-up left it, restored before each batch of iterations, so every
// batch starts from the same particles.
class dambreak : public benchmark::Fixture {
 public:
  void SetUp(benchmark::State& state) override {
    scene_ = &pass_scene(static_cast<std::size_t>(state.range(0)));
    scene_->restore();
  }
  void TearDown(benchmark::State&) override { scene_ = nullptr; }

 protected:
  DamBreak& scene() { return *scene_; }
  Simulation& sim() { return scene_->sim(); }
  double mean_neighbors() { return sim().neighbors().mean_neighbors(); }

 private:
  DamBreak* scene_ = nullptr;
};

inline void sizes(benchmark::internal::Benchmark* b) {
  b->ArgName("N")->Arg(8000)->Arg(32000)->Arg(128000)->UseRealTime()->Unit(benchmark::kMicrosecond);
}

}  // namespace pbf::bench
