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
// One pass, no counts: particles [b * block, (b + 1) * block) write their lists, in the same
// order as fill_neighbors, into list[segment[b] .. segment[b + 1]), offset[i] where particle
// i's list starts; used[b] is how much of its segment block b filled. False when some block's
// lists did not fit its segment (the lists are then incomplete).
bool fill_neighbor_blocks(const CellSearch& search, std::size_t block, std::size_t blocks,
                          const std::uint64_t* segment, std::uint32_t* offset, std::uint32_t* list,
                          std::uint64_t* used);

}  // namespace pbf
