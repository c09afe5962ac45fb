#include "engine/sph/neighbor_grid.hpp"

#include <algorithm>
#include <cmath>
#include <omp.h>

namespace pbf {

namespace {

// The contiguous block of [0, n) that thread t of T handles.
std::size_t block_begin(std::size_t n, int t, int T) { return n * static_cast<std::size_t>(t) / static_cast<std::size_t>(T); }

long clamp_cell(double coordinate, double lo, double cell_size, long dim) {
  const double c = std::floor((coordinate - lo) / cell_size);
  if (!(c >= 0)) return 0;  // also catches NaN
  return c >= static_cast<double>(dim) ? dim - 1 : static_cast<long>(c);
}

}  // namespace

std::size_t NeighborGrid::max_cells(std::size_t n) { return std::max<std::size_t>(4 * n, 1u << 15); }

std::size_t NeighborGrid::cell_of(real x, real y, real z) const {
  const long cx = clamp_cell(x, lo_[0], cell_size_, dims_[0]);
  const long cy = clamp_cell(y, lo_[1], cell_size_, dims_[1]);
  const long cz = clamp_cell(z, lo_[2], cell_size_, dims_[2]);
  return static_cast<std::size_t>((cz * dims_[1] + cy) * dims_[0] + cx);
}

void NeighborGrid::bin(const real* x, const real* y, const real* z, std::size_t n, const Domain& domain, double h) {
  // Cells at least h wide; widen them when the box would need more cells than the cap.
  // Counted in double until they fit: a huge domain over a tiny h must not overflow a long.
  cell_size_ = h;
  const double cap = static_cast<double>(max_cells(n));
  auto cells_along = [&](int a) { return std::max(1.0, std::ceil(domain.extent(a) / cell_size_)); };
  for (;;) {
    const double total = cells_along(0) * cells_along(1) * cells_along(2);
    if (total <= cap) break;
    cell_size_ *= std::max(1.01, std::cbrt(total / cap));  // an infinite total ends in one cell
  }
  for (int a = 0; a < 3; ++a) dims_[a] = static_cast<long>(cells_along(a));
  for (int a = 0; a < 3; ++a) lo_[a] = domain.lo[a];
  const std::size_t ncells = static_cast<std::size_t>(dims_[0] * dims_[1] * dims_[2]);

  cell_.resize(n);
  sorted_.resize(n);
  cell_start_.assign(ncells + 1, 0);
  const int T = omp_get_max_threads();
  histogram_.resize(T);

#pragma omp parallel num_threads(T)
  {
    const int t = omp_get_thread_num();
    const std::size_t begin = block_begin(n, t, T), end = block_begin(n, t + 1, T);
    auto& hist = histogram_[t];
    hist.assign(ncells, 0);
    for (std::size_t i = begin; i < end; ++i) {
      cell_[i] = static_cast<std::uint32_t>(cell_of(x[i], y[i], z[i]));
      ++hist[cell_[i]];
    }
#pragma omp barrier
#pragma omp single
    {
      // Exclusive prefix sum over (cell, thread): thread t's particles of cell c follow
      // those of threads before it, so the order within a cell is ascending index.
      std::uint32_t running = 0;
      for (std::size_t c = 0; c < ncells; ++c) {
        cell_start_[c] = running;
        for (int u = 0; u < T; ++u) {
          const std::uint32_t count = histogram_[u][c];
          histogram_[u][c] = running;
          running += count;
        }
      }
      cell_start_[ncells] = running;
    }
    for (std::size_t i = begin; i < end; ++i) sorted_[hist[cell_[i]]++] = static_cast<std::uint32_t>(i);
  }
}

void NeighborGrid::build_lists(const real* x, const real* y, const real* z, double h) {
  const std::size_t n = cell_.size();
  const real h2 = real(h * h);
  offset_.assign(n + 1, 0);
  const int T = omp_get_max_threads();
  thread_lists_.resize(T);

#pragma omp parallel num_threads(T)
  {
    const int t = omp_get_thread_num();
    const std::size_t begin = block_begin(n, t, T), end = block_begin(n, t + 1, T);
    auto& mine = thread_lists_[t].pairs;
    mine.clear();
    for (std::size_t i = begin; i < end; ++i) {
      const std::size_t before = mine.size();
      const long c = cell_[i];
      const long cx = c % dims_[0], cy = (c / dims_[0]) % dims_[1], cz = c / (dims_[0] * dims_[1]);
      // Cells are numbered x fastest, so the three cells along x of each (y, z) row are one
      // contiguous run of the sorted order: 9 runs instead of 27 cells.
      const long x0 = std::max(0L, cx - 1), x1 = std::min(dims_[0] - 1, cx + 1);
      for (long nz = std::max(0L, cz - 1); nz <= std::min(dims_[2] - 1, cz + 1); ++nz)
        for (long ny = std::max(0L, cy - 1); ny <= std::min(dims_[1] - 1, cy + 1); ++ny) {
          const std::size_t row = static_cast<std::size_t>((nz * dims_[1] + ny) * dims_[0]);
          const std::uint32_t first = cell_start_[row + x0], last = cell_start_[row + x1 + 1];
          for (std::uint32_t s = first; s < last; ++s) {
            const std::uint32_t j = sorted_[s];
            const real dx = x[i] - x[j], dy = y[i] - y[j], dz = z[i] - z[j];
            if (j != i && dx * dx + dy * dy + dz * dz < h2) mine.push_back(j);
          }
        }
      offset_[i + 1] = mine.size() - before;
    }
#pragma omp barrier
#pragma omp single
    {
      for (std::size_t i = 0; i < n; ++i) offset_[i + 1] += offset_[i];
      list_.resize(offset_[n]);
    }
    std::copy(mine.begin(), mine.end(), list_.begin() + static_cast<std::ptrdiff_t>(offset_[begin]));
  }
}

double NeighborGrid::mean_neighbors() const {
  const std::size_t n = particle_count();
  return n == 0 ? 0.0 : static_cast<double>(offset_[n]) / static_cast<double>(n);
}

std::uint32_t NeighborGrid::max_neighbors() const {
  std::uint32_t most = 0;
  for (std::size_t i = 0; i < particle_count(); ++i) most = std::max(most, count(i));
  return most;
}

}  // namespace pbf
