#pragma once
// The distance tests of the neighbour-list build, vectorised across candidates
// (engine/sph/neighbor_search_simd.cpp). NeighborGrid hands them a view of its cells and of
// the positions packed in cell order, so that the candidates of a row of three cells are
// contiguous in memory and a vector compares several at once.
#include <cstddef>
#include <cstdint>

#include "engine/core/real.hpp"

namespace pbf {

struct CellSearch {
  const real *x, *y, *z;            // positions by particle index
  const real *xs, *ys, *zs;         // the same by sorted slot, padded past the end
  const std::uint32_t* sorted;      // particle of each slot, padded past the end
  const std::uint32_t* cell;        // cell of each particle
  const std::uint32_t* cell_start;  // first slot of each cell (cells + 1)
  long dims[3];                     // cells along x, y, z (x fastest)
  real h2;                          // squared search radius
  std::size_t n;                    // particles
};

// counts[i] = the number of particles j != i with |x_i - x_j|^2 < h^2 (in parallel).
void count_neighbors(const CellSearch& search, std::uint32_t* counts);
// Writes particle i's neighbours to list[offset[i] ...], rows of cells in a fixed order
// (z, then y), slots ascending within a row (in parallel).
void fill_neighbors(const CellSearch& search, const std::uint32_t* offset, std::uint32_t* list);
// One pass, no counts: particles [begin, end) write their lists, in the same order as
// fill_neighbors, into list[first .. last), offset[i] where particle i's list starts. Returns
// how many indices they wrote, or kBlockFull when their lists did not fit (they are then
// incomplete). Opens no parallel region: the caller's threads take blocks.
constexpr std::uint64_t kBlockFull = ~std::uint64_t(0);
std::uint64_t fill_neighbor_block(const CellSearch& search, std::size_t begin, std::size_t end, std::uint32_t* list,
                                  std::uint64_t first, std::uint64_t last, std::uint32_t* offset, std::uint32_t& most);

}  // namespace pbf
