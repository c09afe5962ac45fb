// The two neighbour passes of a PBF iteration, timed apart, where the engine exposes them:
// engine/sph/pair_sums.hpp's constraint_sums (density and constraint gradients) and
// constraint_corrections (the position corrections), the fluid's pair sums the pbf fix
// calls; its per-particle work (the walls, lambda, moving the particles) is not in them
// (dambreak/pbf_iteration has it all).

#include <benchmark/benchmark.h>

#include <stdexcept>
#include <vector>

#include "bench/fixture.hpp"
#include "bench/flops.hpp"
#include "engine/core/parallel.hpp"
#include "engine/sph/pair_sums.hpp"

namespace pbf::bench {

namespace {

PairInput pairs_of(Simulation& sim) {
  const auto& P = sim.particles();
  return PairInput{sim.neighbors(), P.x(), P.y(), P.z(), P.mass(), uniform_mass(P.mass(), P.size()),
                   sim.kernels(), P.size()};
}

}  // namespace

// The density-and-gradient pass (per pair as dambreak/pbf_iteration's first pass).
BENCHMARK_DEFINE_F(dambreak, pbf_constraint_sums)(benchmark::State& state) {
  const std::size_t n = scene().size();
  std::vector<real> sums[5];
  for (auto& s : sums) s.resize(n);
  const real inv_rho0 = real(1 / sim().rest_density());
  const PairInput in = pairs_of(sim());
  LoopClock clock;
  for (auto _ : state) {
    for_blocks(n, [&](std::size_t begin, std::size_t end) {
      constraint_sums(in, begin, end, inv_rho0, sums[0].data(), sums[1].data(), sums[2].data(), sums[3].data(),
                      sums[4].data());
    });
    benchmark::ClobberMemory();
  }
  report(state, clock, n, mean_neighbors(), kPbfLambdaPerPair, 0);
}
BENCHMARK_REGISTER_F(dambreak, pbf_constraint_sums)->Apply(sizes);

// The correction pass, with the multipliers the warm-up's last iteration left in the field
// "lambda" and the pbf defaults (no artificial pressure).
BENCHMARK_DEFINE_F(dambreak, pbf_constraint_corrections)(benchmark::State& state) {
  auto& P = sim().particles();
  const std::size_t n = P.size();
  const auto lambda = P.find("lambda");
  if (!lambda) throw std::runtime_error("dam break: no field 'lambda'");
  std::vector<real> d[3];
  for (auto& c : d) c.resize(n);
  const real inv_rho0 = real(1 / sim().rest_density());
  const PairInput in = pairs_of(sim());
  LoopClock clock;
  for (auto _ : state) {
    for_blocks(n, [&](std::size_t begin, std::size_t end) {
      constraint_corrections(in, begin, end, P.data(*lambda), inv_rho0, 0, 1, 4, d[0].data(), d[1].data(),
                             d[2].data());
    });
    benchmark::ClobberMemory();
  }
  report(state, clock, n, mean_neighbors(), kPbfCorrectionPerPair, 0);
}
BENCHMARK_REGISTER_F(dambreak, pbf_constraint_corrections)->Apply(sizes);

}  // namespace pbf::bench
