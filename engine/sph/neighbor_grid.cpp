#include "engine/sph/neighbor_grid.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <omp.h>

#include <fmt/format.h>

#include "engine/core/error.hpp"
#include "engine/core/parallel.hpp"
#include "engine/sph/neighbor_search_simd.hpp"

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

// The offsets are 32-bit (4 bytes a particle instead of 8): lists of more pairs are refused.
constexpr std::uint64_t kMostPairs = 0xFFFFFFFFu - NeighborGrid::kListPadding;

// 2^23 cells (203^3: a 2-million-particle scene at h = 2 spacings fills a quarter of them)
// take 32 MiB an array (the cell starts, and a histogram per thread).
std::size_t NeighborGrid::max_cells() { return std::size_t{1} << 23; }

GridGeometry GridGeometry::of(const Domain& domain, double h) {
  // Cells at least h wide; widen them when the box would need more cells than the cap. The
  // particle count plays no part: a scene that fills up or drains keeps its grid, so its
  // neighbour order and its ranks' boxes. Counted in double until they fit: a huge domain over
  // a tiny h must not overflow a long.
  double size = h;
  const double cap = static_cast<double>(NeighborGrid::max_cells());
  auto cells_along = [&](int a) { return std::max(1.0, std::ceil(domain.extent(a) / size)); };
  for (;;) {
    const double total = cells_along(0) * cells_along(1) * cells_along(2);
    if (total <= cap) break;
    size *= std::max(1.01, std::cbrt(total / cap));  // an infinite total ends in one cell
  }
  GridGeometry g;
  for (int a = 0; a < 3; ++a) {
    g.lo[a] = domain.lo[a];
    g.periodic[a] = domain.periodic[a];
    g.dims[a] = static_cast<long>(cells_along(a));
    g.cell_size[a] = size;
    if (domain.periodic[a]) {  // whole cells over the period, two at least (the period is 2 h or more)
      g.dims[a] = std::max(2L, static_cast<long>(std::floor(domain.extent(a) / size)));
      g.cell_size[a] = domain.extent(a) / static_cast<double>(g.dims[a]);
    }
  }
  return g;
}

long GridGeometry::cell_along(int axis, double coordinate) const {
  if (!periodic[axis]) return clamp_cell(coordinate, lo[axis], cell_size[axis], dims[axis]);
  const long n = dims[axis];
  const double c = std::floor((coordinate - lo[axis]) / cell_size[axis]);
  if (!(c == c)) return 0;
  return static_cast<long>(std::clamp(c, double(-n - 2), double(2 * n + 1)));
}

CellRange GridGeometry::grown(const CellRange& r) const {
  CellRange g;
  for (int a = 0; a < 3; ++a) {
    g.lo[a] = periodic[a] ? r.lo[a] - 1 : std::max(0L, r.lo[a] - 1);
    g.hi[a] = periodic[a] ? r.hi[a] + 1 : std::min(dims[a], r.hi[a] + 1);
  }
  return g;
}

std::size_t NeighborGrid::cell_of(real x, real y, real z) const {
  const real p[3] = {x, y, z};
  long c[3];
  for (int a = 0; a < 3; ++a)
    c[a] = std::clamp(geometry_.cell_along(a, p[a]) - range_.lo[a], 0L, dims_[a] - 1);
  return static_cast<std::size_t>((c[2] * dims_[1] + c[1]) * dims_[0] + c[0]);
}

void NeighborGrid::bin(const real* x, const real* y, const real* z, std::size_t n, const Domain& domain, double h) {
  const GridGeometry g = GridGeometry::of(domain, h);
  bin(x, y, z, n, g, CellRange::all(g));
}

void NeighborGrid::bin(const real* x, const real* y, const real* z, std::size_t n, const GridGeometry& geometry,
                       const CellRange& range, const std::int64_t* key) {
  geometry_ = geometry;
  range_ = range;
  for (int a = 0; a < 3; ++a) dims_[a] = std::max(1L, range.hi[a] - range.lo[a]);
  const std::size_t ncells = static_cast<std::size_t>(dims_[0] * dims_[1] * dims_[2]);

  cell_.resize(n);
  sorted_.resize(n + kListPadding);  // the padding (zeros) lets a vector load run past the last slot
  std::fill(sorted_.begin() + static_cast<std::ptrdiff_t>(n), sorted_.end(), 0u);
  cell_start_.resize(ncells + 1);  // every entry is written below
  const int T = omp_get_max_threads();
  histogram_.resize(T);
  cells_counted_.resize(T);

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
    // Exclusive prefix sum over (cell, thread): thread t's particles of cell c follow those of
    // threads before it, so the order within a cell is ascending index. In parallel, over a
    // range of cells per thread: first each range's total, then the sums within the ranges.
    const std::size_t first_cell = block_begin(ncells, t, T), end_cell = block_begin(ncells, t + 1, T);
#pragma omp barrier
    std::uint32_t counted = 0;
    for (std::size_t c = first_cell; c < end_cell; ++c)
      for (int u = 0; u < T; ++u) counted += histogram_[u][c];
    cells_counted_[t] = counted;
#pragma omp barrier
    std::uint32_t running = 0;
    for (int u = 0; u < t; ++u) running += cells_counted_[u];
    for (std::size_t c = first_cell; c < end_cell; ++c) {
      cell_start_[c] = running;
      for (int u = 0; u < T; ++u) {
        const std::uint32_t count = histogram_[u][c];
        histogram_[u][c] = running;
        running += count;
      }
    }
    if (t == T - 1) cell_start_[ncells] = running;
#pragma omp barrier
    for (std::size_t i = begin; i < end; ++i) {
      sorted_[hist[cell_[i]]++] = static_cast<std::uint32_t>(i);
    }
    if (key) {  // in the same region: the threads meet once more, not twice
#pragma omp barrier
#pragma omp for schedule(static) nowait  // the region's end waits
      for (std::size_t c = 0; c < ncells; ++c) order_cell(c, key);
    }
  }
}

// Cells hold a few particles, mostly in order already: insertion sort.
void NeighborGrid::order_cell(std::size_t c, const std::int64_t* key) {
  for (std::uint32_t s = cell_start_[c] + 1; s < cell_start_[c + 1]; ++s) {
    const std::uint32_t moving = sorted_[s];
    std::uint32_t t = s;
    for (; t > cell_start_[c] && key[sorted_[t - 1]] > key[moving]; --t) sorted_[t] = sorted_[t - 1];
    sorted_[t] = moving;
  }
}

void NeighborGrid::order_cells_by(const std::int64_t* key) {
  const std::size_t ncells = cell_count();
#pragma omp parallel for schedule(static)
  for (std::size_t c = 0; c < ncells; ++c) order_cell(c, key);
}

void NeighborGrid::offset_neighbors(std::uint32_t below, std::uint32_t by) {
  for_particles(particle_count(), [&](std::size_t i) {
    for (std::uint32_t k = offset_[i]; k < offset_[i + 1]; ++k)
      if (list_[k] < below) list_[k] += by;
  });
}

void NeighborGrid::build_lists(const real* x, const real* y, const real* z, double h, std::size_t listed) {
  const std::size_t binned = cell_.size(), n = std::min(listed, binned);
  for (auto& packed : packed_) packed.resize(binned + kListPadding);
  const CellSearch search{x, y, z, packed_[0].data(), packed_[1].data(), packed_[2].data(), sorted_.data(),
                          cell_.data(), cell_start_.data(), {dims_[0], dims_[1], dims_[2]},
                          real(h * h), n};
  offset_.resize(n + 1);
  bool packed = false;
  one_pass_ = fill_in_one_pass(search, packed);
  if (!one_pass_) {
    if (!packed) {
#pragma omp parallel for schedule(static)
      for (std::size_t slot = 0; slot < binned; ++slot) pack(search, slot);
    }
    fill_in_two_passes(search);
  }
  // Each block's pairs, where the next build's segments start.
  const std::size_t blocks = (n + kBlock - 1) / kBlock;
  block_pairs_.resize(blocks);
  for (std::size_t b = 0; b < blocks; ++b)
    block_pairs_[b] = offset_[std::min(n, (b + 1) * kBlock)] - offset_[b * kBlock];
}

// The positions in slot order, which the distance tests load as vectors.
void NeighborGrid::pack(const CellSearch& search, std::size_t slot) {
  const std::uint32_t i = sorted_[slot];
  packed_[0][slot] = search.x[i];
  packed_[1][slot] = search.y[i];
  packed_[2][slot] = search.z[i];
}

// Lists move little from one step to the next, so the last build's pairs per block of
// particles say where each block's lists will fit: each block writes into its own segment
// (its last pairs, an eighth more and 64) in one pass, and the segments are then moved
// together in block order. The distance tests run once, not twice (count, then fill); the
// lists are the same. A block that does not fit sends the build to two passes. All of it,
// the positions' packing first, in one parallel region.
bool NeighborGrid::fill_in_one_pass(const CellSearch& search, bool& packed) {
  const std::size_t n = search.n, blocks = (n + kBlock - 1) / kBlock, binned = cell_.size();
  if (blocks == 0 || block_pairs_.size() != blocks) return false;
  segment_.resize(blocks + 1);
  segment_[0] = 0;
  for (std::size_t b = 0; b < blocks; ++b) segment_[b + 1] = segment_[b] + block_pairs_[b] + block_pairs_[b] / 8 + 64;
  if (segment_[blocks] > kMostPairs) return false;  // the two passes say whether the pairs fit
  const std::size_t room = segment_[blocks] + kListPadding;
  if (list_.capacity() < room) {  // as in the two passes: the old lists go first
    std::vector<std::uint32_t>().swap(list_);
    list_.reserve(room + room / 4);
  }
  if (list_.size() < room) list_.resize(room);
  used_.resize(blocks);
  block_most_.resize(blocks);
  packed = true;
  bool fits = true;
#pragma omp parallel
  {
#pragma omp for schedule(static)
    for (std::size_t slot = 0; slot < binned; ++slot) pack(search, slot);
#pragma omp for schedule(dynamic, 1)
    for (std::size_t b = 0; b < blocks; ++b)
      used_[b] = fill_neighbor_block(search, b * kBlock, std::min(n, (b + 1) * kBlock), list_.data(), segment_[b],
                                     segment_[b + 1], offset_.data(), block_most_[b]);
#pragma omp single
    {
      std::uint64_t at = 0;
      for (std::size_t b = 0; b < blocks && fits; ++b) {
        fits = used_[b] != kBlockFull;
        if (!fits) break;
        if (segment_[b] != at)
          std::memmove(list_.data() + at, list_.data() + segment_[b], used_[b] * sizeof(std::uint32_t));
        segment_[b] -= at;  // now how far block b's lists moved
        at += used_[b];
      }
      if (fits) {
        offset_[n] = static_cast<std::uint32_t>(at);
        std::fill(list_.begin() + static_cast<std::ptrdiff_t>(at),
                  list_.begin() + static_cast<std::ptrdiff_t>(at + kListPadding), 0u);
      }
    }
    if (fits) {
#pragma omp for schedule(static) nowait  // the region's end waits
      for (std::size_t i = 0; i < n; ++i) offset_[i] -= static_cast<std::uint32_t>(segment_[i / kBlock]);
    }
  }
  if (!fits) return false;
  most_ = *std::max_element(block_most_.begin(), block_most_.end());
  return true;
}

void NeighborGrid::fill_in_two_passes(const CellSearch& search) {
  const std::size_t n = search.n;
  offset_[0] = 0;
  count_neighbors(search, offset_.data() + 1);
  std::uint64_t pairs = 0;  // the running sum, checked against the offsets' range
  most_ = 0;
  for (std::size_t i = 0; i < n; ++i) {
    most_ = std::max(most_, offset_[i + 1]);
    pairs += offset_[i + 1];
    if (pairs > kMostPairs)
      throw Error(fmt::format("{} particles have more than {} neighbours in all ({:.3g} per particle): the fluid has "
                              "collapsed (a time step too large?), or the scene is beyond what the lists can hold",
                              n, kMostPairs, double(pairs) / double(i + 1)));
    offset_[i + 1] = static_cast<std::uint32_t>(pairs);
  }
  const std::size_t total = offset_[n] + kListPadding;
  if (list_.capacity() < total) {
    // Room to grow for a while. The old lists are rebuilt anyway: freed before the larger
    // array is taken, so that the two never take memory at once.
    std::vector<std::uint32_t>().swap(list_);
    list_.reserve(total + total / 4);
  }
  list_.resize(std::max(list_.size(), total));
  std::fill(list_.begin() + static_cast<std::ptrdiff_t>(offset_[n]), list_.begin() + static_cast<std::ptrdiff_t>(total), 0u);
  fill_neighbors(search, offset_.data(), list_.data());
}

double NeighborGrid::mean_neighbors() const {
  const std::size_t n = particle_count();
  return n == 0 ? 0.0 : static_cast<double>(offset_[n]) / static_cast<double>(n);
}


}  // namespace pbf
