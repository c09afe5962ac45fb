#pragma once
// Deterministic reductions: partial sums over fixed blocks of particles (independent of
// the thread count), combined in block order, so a sum has the same bits on 1 or 64 threads.
#include <cstddef>
#include <vector>

namespace pbf {

inline constexpr std::size_t kReduceBlock = 2048;

// Sums term(i) for i in [0, n); Term returns double.
template <class Term>
double deterministic_sum(std::size_t n, Term&& term) {
  const std::size_t blocks = (n + kReduceBlock - 1) / kReduceBlock;
  // Kept between calls by the thread that takes the sum (outside parallel regions), so that a
  // step allocates nothing; the threads of the loop write through a plain pointer (each has
  // a thread_local of its own).
  static thread_local std::vector<double> kept;
  kept.assign(blocks, 0.0);
  double* partial = kept.data();
#pragma omp parallel for schedule(static)
  for (std::size_t b = 0; b < blocks; ++b) {
    const std::size_t end = (b + 1) * kReduceBlock < n ? (b + 1) * kReduceBlock : n;
    double s = 0;
    for (std::size_t i = b * kReduceBlock; i < end; ++i) s += term(i);
    partial[b] = s;
  }
  double total = 0;
  for (std::size_t b = 0; b < blocks; ++b) total += partial[b];
  return total;
}

}  // namespace pbf
