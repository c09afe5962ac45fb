// Micro-benchmarks of the engine's passes on the PBF dam break (bench/scene.hpp) at about 8k,
// 32k and 128k particles (the argument is the target count; the counter `particles` is the
// scene's). Each benchmark times one pass as the run loop calls it, through public
// interfaces only: NeighborGrid::bin and build_lists, the fixes' hooks through the Fix
// interface, Simulation::summed_density and Simulation::run. The counters are those of
// bench/fixture.hpp.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstddef>
#include <exception>
#include <vector>

#include "bench/fixture.hpp"
#include "bench/flops.hpp"
#include "bench/scene.hpp"
#include "engine/sph/neighbor_grid.hpp"

namespace pbf::bench {

namespace {

// The PBF iteration timed: a middle one (the last of a fixed count also measures the density
// error for the solver report; with one_sided and no pressure the others are identical).
constexpr int kTimedIteration = 1;
// The stepping scene starts again after this much simulated time (the surge then changes the
// scene's cost; particles leaving the column are fine, the far wall is 0.8 m away).
constexpr double kMaxStepTime = 0.5;

}  // namespace

// Binning into the grid's cells (counting sort), with a grid of its own.
BENCHMARK_DEFINE_F(dambreak, grid_bin)(benchmark::State& state) {
  const auto& P = sim().particles();
  NeighborGrid grid;
  LoopClock clock;
  for (auto _ : state) {
    grid.bin(P.x(), P.y(), P.z(), P.size(), sim().domain(), sim().kernel_radius());
    benchmark::ClobberMemory();
  }
  report(state, clock, P.size(), mean_neighbors(), 0, 0);
}
BENCHMARK_REGISTER_F(dambreak, grid_bin)->Apply(sizes);

// The neighbour lists from a binned grid (the distance tests: an estimate, bench/flops.hpp).
BENCHMARK_DEFINE_F(dambreak, build_lists)(benchmark::State& state) {
  const auto& P = sim().particles();
  NeighborGrid grid;
  grid.bin(P.x(), P.y(), P.z(), P.size(), sim().domain(), sim().kernel_radius());
  LoopClock clock;
  for (auto _ : state) {
    grid.build_lists(P.x(), P.y(), P.z(), sim().kernel_radius());
    benchmark::ClobberMemory();
  }
  report(state, clock, P.size(), grid.mean_neighbors(), kListsPerNeighbor, 0);
}
BENCHMARK_REGISTER_F(dambreak, build_lists)->Apply(sizes);

// One PBF constraint iteration (density and lambda pass, then the correction pass), the pbf
// fix's constraint hook. Positions move by each iteration's correction; over a batch they
// converge on the constraint, with the lists of the warm-up positions.
BENCHMARK_DEFINE_F(dambreak, pbf_iteration)(benchmark::State& state) {
  Fix& pbf = scene().fix("pbf");
  scene().positions_changed();
  LoopClock clock;
  for (auto _ : state) pbf.constraint(sim(), kTimedIteration);
  report(state, clock, scene().size(), mean_neighbors(), kPbfIterationPerPair, kPbfIterationPerParticle);
  if (!finite(sim())) state.SkipWithError("positions became NaN or infinite");
}
BENCHMARK_REGISTER_F(dambreak, pbf_iteration)->Apply(sizes);

// The SPH density with the walls' share that vorticity and xsph read (the first of them in a
// step pays for it; in the benchmarks of those two it is cached).
BENCHMARK_DEFINE_F(dambreak, summed_density)(benchmark::State& state) {
  LoopClock clock;
  for (auto _ : state) {
    sim().positions_changed();  // invalidates the cached density, not the lists
    benchmark::DoNotOptimize(sim().summed_density().data());
  }
  report(state, clock, scene().size(), mean_neighbors(), kDensityPerPair, kDensityPerParticle);
}
BENCHMARK_REGISTER_F(dambreak, summed_density)->Apply(sizes);

// Vorticity confinement: the velocity curl, then the gradient of its magnitude and the
// velocity change (the vorticity fix's velocity_post hook).
BENCHMARK_DEFINE_F(dambreak, vorticity)(benchmark::State& state) {
  Fix& vorticity = scene().fix("vorticity");
  scene().velocities_changed();
  LoopClock clock;
  for (auto _ : state) vorticity.velocity_post(sim());
  report(state, clock, scene().size(), mean_neighbors(), kVorticityPerPair, kVorticityPerParticle);
  if (!finite(sim())) state.SkipWithError("velocities became NaN or infinite");
}
BENCHMARK_REGISTER_F(dambreak, vorticity)->Apply(sizes);

// XSPH viscosity (the xsph fix's velocity_post hook).
BENCHMARK_DEFINE_F(dambreak, xsph)(benchmark::State& state) {
  Fix& xsph = scene().fix("xsph");
  scene().velocities_changed();
  LoopClock clock;
  for (auto _ : state) xsph.velocity_post(sim());
  report(state, clock, scene().size(), mean_neighbors(), kXsphPerPair, kXsphPerParticle);
  if (!finite(sim())) state.SkipWithError("velocities became NaN or infinite");
}
BENCHMARK_REGISTER_F(dambreak, xsph)->Apply(sizes);

// The bare walk over the neighbour lists that every pass makes: each particle's neighbours,
// their coordinates gathered, and nothing computed but the squared distances' sum. No physics,
// so what limits it is the machine's memory (the gathers through the shared L3); its speed-up
// from 1 to 2 threads (OMP_NUM_THREADS) is the most a pass can get on this machine
// (docs/performance.md, "The targets missed, and why").
BENCHMARK_DEFINE_F(dambreak, list_walk)(benchmark::State& state) {
  const auto& P = sim().particles();
  const auto& grid = sim().neighbors();
  const real *x = P.x(), *y = P.y(), *z = P.z();
  const auto n = static_cast<std::ptrdiff_t>(P.size());
  std::vector<real> sums(P.size());
  LoopClock clock;
  for (auto _ : state) {
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t i = 0; i < n; ++i) {
      real sum = 0;
      grid.for_each_neighbor(static_cast<std::size_t>(i), x, y, z,
                             [&](std::uint32_t, real, real, real, real r2) { sum += r2; });
      sums[static_cast<std::size_t>(i)] = sum;
    }
    benchmark::DoNotOptimize(sums.data());
    benchmark::ClobberMemory();
  }
  report(state, clock, P.size(), mean_neighbors(), 0, 0);
}
BENCHMARK_REGISTER_F(dambreak, list_walk)->Apply(sizes);

// A whole step, sim.run(1): every stage, the lists, the reordering every 20 steps, the
// checks, and what a run costs on top of its steps (each fix's init, the timing table).
// Its own scene, which it advances; started again after kMaxStepTime of simulated time.
void step(benchmark::State& state) {
  const auto target = static_cast<std::size_t>(state.range(0));
  DamBreak* scene = &step_scene(target);
  double neighbor_sum = 0;
  LoopClock clock;
  for (auto _ : state) {
    if (scene->time_since_warmup() > kMaxStepTime) {
      state.PauseTiming();
      clock.pause();
      scene = &rebuild_step_scene(target);
      clock.resume();
      state.ResumeTiming();
    }
    try {
      scene->sim().run(1);
    } catch (const std::exception& e) {
      state.SkipWithError(e.what());
      break;
    }
    neighbor_sum += scene->sim().neighbors().mean_neighbors();
  }
  const double nb = state.iterations() ? neighbor_sum / static_cast<double>(state.iterations()) : 0;
  // A step: its constraint iterations, the summed density, vorticity, xsph and the lists.
  const double iterations = scene->sim().solver_report().constraints.iterations;
  const double per_pair = iterations * kPbfIterationPerPair + kDensityPerPair + kVorticityPerPair +
                          kXsphPerPair + kListsPerNeighbor;
  const double per_particle = iterations * kPbfIterationPerParticle + kDensityPerParticle +
                              kVorticityPerParticle + kXsphPerParticle;
  report(state, clock, scene->size(), nb, per_pair, per_particle);
  // Steps the scene has taken since its warm-up (it starts again after kMaxStepTime).
  state.counters["steps_since_warmup"] = std::round(scene->time_since_warmup() / scene->sim().timestep());
}
BENCHMARK(step)->Name("dambreak/step")->Apply(sizes);

}  // namespace pbf::bench
