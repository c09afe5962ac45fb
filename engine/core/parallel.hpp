#pragma once
// The engine's parallel loops over particles, and deterministic reductions.
//
// Every parallel region is a meeting of the threads: each waits at its end for the slowest,
// and on a machine shared with other work the slowest may be a thread that is not running
// at all. So a pass does in one region all that its particles need (a pair sum and the
// per-particle work after it), and a step opens few regions (docs/design.md, "Threads";
// tests/test_parallel_regions.cpp holds the dam break's step to its budget).
//
// for_blocks hands out blocks of particles to whichever thread is free (dynamic scheduling):
// a thread that the machine's other work slows down takes fewer blocks instead of holding
// the others up. Which thread computes a particle never changes its bits, as every
// per-particle result is computed from the particle's own data and its neighbours' in a fixed
// order; sums over particles use exact accumulators, merged in thread order.
//
// Deterministic sums: each thread adds its terms into an exact accumulator
// (engine/core/exact_sum.hpp) and the accumulators are merged exactly, so a sum is the exact
// sum of its terms rounded once: the same bits on 1 or 64 threads, in any memory order of the
// particles (and, merged as integers, across processes).
#include <omp.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <vector>

#include "engine/core/exact_sum.hpp"
#include "engine/distributed/comm.hpp"

namespace pbf {

// Particles per block of a pass over the neighbour lists (for_blocks): enough work to make
// handing it out cheap (a few microseconds of a pair sum), few enough that the last blocks
// even the threads out.
constexpr std::size_t kParticleBlock = 256;
// Particles per block of a pass that streams through arrays (for_particles, the sums): each
// thread reads long runs, which the hardware prefetchers follow, and two threads seldom
// write the cache line where their blocks meet (measured: blocks of 256 made the prediction
// of positions 3 to 4 times as slow).
constexpr std::size_t kStreamBlock = 4096;

// Calls body(begin, end) for the blocks [begin, end) of [0, n), `block` particles each, in
// one parallel region; body may index per-thread state by omp_get_thread_num().
template <class Body>
void for_blocks(std::size_t n, Body&& body, std::size_t block = kParticleBlock) {
  const std::size_t blocks = (n + block - 1) / block;
#pragma omp parallel for schedule(dynamic, 1)
  for (std::size_t b = 0; b < blocks; ++b) body(b * block, std::min(n, (b + 1) * block));
}

// Calls body(i) for each particle i in [0, n), in one parallel region. The bodies of
// different particles must be independent (each writes only particle i's values): the
// compiler may then run several at once in vectors (the same IEEE operations per lane, so
// the same bits).
template <class Body>
void for_particles(std::size_t n, Body&& body) {
  for_blocks(
      n,
      [&](std::size_t begin, std::size_t end) {
#pragma omp simd
        for (std::size_t i = begin; i < end; ++i) body(i);
      },
      kStreamBlock);
}

// The first particle i in [0, n) for which each of K tests holds: tests(i) returns a
// std::array<bool, K>; n for a test that no particle meets. One parallel region.
template <std::size_t K, class Tests>
std::array<std::size_t, K> first_particles(std::size_t n, Tests&& tests) {
  std::size_t first[K];
  for (std::size_t& f : first) f = n;
#pragma omp parallel for schedule(dynamic, kStreamBlock) reduction(min : first[:K])
  for (std::size_t i = 0; i < n; ++i) {
    const std::array<bool, K> met = tests(i);
    for (std::size_t k = 0; k < K; ++k)
      if (met[k]) first[k] = std::min(first[k], i);
  }
  std::array<std::size_t, K> found;
  std::copy(first, first + K, found.begin());
  return found;
}

// The first particle i in [0, n) for which test(i) holds, n if none.
template <class Test>
std::size_t first_particle(std::size_t n, Test&& test) {
  return first_particles<1>(n, [&](std::size_t i) { return std::array<bool, 1>{bool(test(i))}; })[0];
}

// One exact accumulator per thread, kept between calls by the thread that owns it, so that a
// step allocates nothing; total() merges them in thread order. One ThreadSums<K> at a time
// per thread that opens regions (they share the kept accumulators).
template <std::size_t K>
class ThreadSums {
 public:
  // Zeroed accumulators for the threads of the next parallel region (taken on the thread
  // that opens it).
  ThreadSums() : sums_(kept()) { sums_.assign(static_cast<std::size_t>(omp_get_max_threads()), {}); }
  // The calling thread's accumulators.
  std::array<ExactSum, K>& mine() { return sums_[static_cast<std::size_t>(omp_get_thread_num())]; }
  // The K sums over every thread (and every rank: a collective call), rounded once each.
  std::array<double, K> total(bool across_ranks) const {
    std::array<double, K> values{};
    for (std::size_t k = 0; k < K; ++k) {
      ExactSum sum;
      for (const auto& thread : sums_) sum.merge(thread[k]);
      if (across_ranks) comm::sum(sum);
      values[k] = sum.value();
    }
    return values;
  }

 private:
  static std::vector<std::array<ExactSum, K>>& kept() {
    static thread_local std::vector<std::array<ExactSum, K>> sums;
    return sums;
  }
  std::vector<std::array<ExactSum, K>>& sums_;
};

// The K sums over i in [0, n) of terms(i), a std::array<double, K>, each exact and rounded
// once; across_ranks: and over every rank's terms (a collective call). One parallel region
// for all K.
template <std::size_t K, class Terms>
std::array<double, K> deterministic_sums(std::size_t n, Terms&& terms, bool across_ranks = false) {
  ThreadSums<K> sums;
  for_blocks(
      n,
      [&](std::size_t begin, std::size_t end) {
        auto& mine = sums.mine();
        for (std::size_t i = begin; i < end; ++i) {
          const std::array<double, K> t = terms(i);
          for (std::size_t k = 0; k < K; ++k) mine[k].add(t[k]);
        }
      },
      kStreamBlock);
  return sums.total(across_ranks);
}

// Sums term(i) for i in [0, n); Term returns double. across_ranks: and over every rank's
// terms (a collective call), as one exact sum.
template <class Term>
double deterministic_sum(std::size_t n, Term&& term, bool across_ranks = false) {
  return deterministic_sums<1>(
      n, [&](std::size_t i) { return std::array<double, 1>{term(i)}; }, across_ranks)[0];
}

}  // namespace pbf
