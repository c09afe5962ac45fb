#pragma once
// Deterministic reductions: sums whose bits do not depend on how the terms are shared out.
// Each thread adds its terms into an exact accumulator (engine/core/exact_sum.hpp) and the
// accumulators are merged exactly, so the sum is the exact sum of the terms rounded once: the
// same bits on 1 or 64 threads, in any memory order of the particles (and, merged as integers,
// across processes).
#include <omp.h>

#include <cstddef>
#include <vector>

#include "engine/core/exact_sum.hpp"
#include "engine/distributed/comm.hpp"

namespace pbf {

// Sums term(i) for i in [0, n); Term returns double. across_ranks: and over every rank's
// terms (a collective call), as one exact sum.
template <class Term>
double deterministic_sum(std::size_t n, Term&& term, bool across_ranks = false) {
  // Kept between calls by the thread that takes the sum (outside parallel regions), so that a
  // step allocates nothing; one accumulator per thread of the loop.
  static thread_local std::vector<ExactSum> kept;
  kept.assign(static_cast<std::size_t>(omp_get_max_threads()), ExactSum{});
  ExactSum* partial = kept.data();
#pragma omp parallel
  {
    ExactSum& mine = partial[omp_get_thread_num()];
#pragma omp for schedule(static)
    for (std::size_t i = 0; i < n; ++i) mine.add(term(i));
  }
  ExactSum total;
  for (const ExactSum& p : kept) total.merge(p);
  if (across_ranks) comm::sum(total);
  return total.value();
}

}  // namespace pbf
