// The sums over particles: deterministic_sum (exact, engine/core/exact_sum.hpp) against a plain
// sum in one thread, over the values of a 33,750-particle field (uniform in [0, 0.01), the
// scale of PBF's compression), so that docs/design.md's cost per addition is measured here.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "engine/core/parallel.hpp"

namespace pbf::bench {

namespace {

constexpr std::size_t kValues = 33750;

const std::vector<float>& field() {
  static const std::vector<float> values = [] {
    std::vector<float> v(kValues);
    std::mt19937 rng(1);
    std::uniform_real_distribution<float> u(0.0f, 0.01f);
    for (auto& x : v) x = u(rng);
    return v;
  }();
  return values;
}

void exact_sum(benchmark::State& state) {
  const auto& v = field();
  for (auto _ : state) benchmark::DoNotOptimize(deterministic_sum(v.size(), [&](std::size_t i) { return double(v[i]); }));
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * v.size()));
}
BENCHMARK(exact_sum)->Name("reduction/deterministic_sum");

void plain_sum(benchmark::State& state) {
  const auto& v = field();
  for (auto _ : state) {
    double s = 0;
    for (float x : v) s += double(x);
    benchmark::DoNotOptimize(s);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * v.size()));
}
BENCHMARK(plain_sum)->Name("reduction/plain_sum");

}  // namespace

}  // namespace pbf::bench
