#pragma once
// Uniform grid with cells at least h wide, built by a parallel counting sort
// (per-thread histograms, a prefix sum, a stable scatter: no locks, no atomics), and
// compressed neighbour lists built from it once per step in two passes straight into
// the final array: count each particle's neighbours, a prefix sum, then fill. Both passes
// test candidates with vectors, over positions packed in cell order
// (engine/sph/neighbor_search_simd.hpp).
//
// Positions outside the domain fall into the edge cells (clamping keeps any two points
// closer than h in the same or adjacent cells), and the cell count is capped, so memory
// follows the particle count, not the box volume over h^3. Along a periodic axis the cells
// tile the period exactly (L / floor(L / size) wide, at least two of them) and are not
// clamped: the periodic images (ghosts at x +/- L) fall into the cells beyond the faces,
// the same cells on every rank. Neighbour order is fixed
// (the 3 x 3 x 3 cells in a fixed order, ascending index within a cell): the lists, and everything
// summed over them, are the same at any thread count. The engine orders each cell's particles
// by id (order_cells_by) before it builds lists, so a list's order depends on the particles'
// positions and ids only, never on memory order or on when the list was built; and it keeps
// memory in the same order (reordering every 20 steps), so that neighbours sit near in memory.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "engine/core/domain.hpp"
#include "engine/core/real.hpp"

namespace pbf {

struct CellSearch;  // engine/sph/neighbor_search_simd.hpp

struct GridGeometry;

// A box of cells [lo, hi) along each axis.
struct CellRange {
  long lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  static CellRange all(const GridGeometry& g);
  bool empty() const { return hi[0] <= lo[0] || hi[1] <= lo[1] || hi[2] <= lo[2]; }
  bool contains(const long c[3]) const {
    return c[0] >= lo[0] && c[0] < hi[0] && c[1] >= lo[1] && c[1] < hi[1] && c[2] >= lo[2] && c[2] < hi[2];
  }
};

// The cells of the whole domain, at least h wide, widened when the domain would need more
// than max_cells(). They depend on the domain and h alone, so every rank of a distributed run
// has the same geometry (a particle's neighbours come in the same order whichever rank lists
// them), and a run whose particle count changes keeps it.
struct GridGeometry {
  double lo[3] = {0, 0, 0};
  double cell_size[3] = {1, 1, 1};  // along each axis (equal, but along a periodic one)
  long dims[3] = {1, 1, 1};          // cells [0, dims) cover the domain
  bool periodic[3] = {false, false, false};
  static GridGeometry of(const Domain& domain, double h);
  // The cell along `axis` of a coordinate, clamped into the grid (NaN: cell 0); along a
  // periodic axis not clamped to the grid, only to [-dims - 2, 2 dims + 2) (positions lie
  // within a period of the faces: images, particles that crossed a face in this step).
  long cell_along(int axis, double coordinate) const;
  // The cells within one cell of `r`: clamped into the grid, but along a periodic axis.
  CellRange grown(const CellRange& r) const;
  bool operator==(const GridGeometry&) const = default;
};

inline CellRange CellRange::all(const GridGeometry& g) { return {{0, 0, 0}, {g.dims[0], g.dims[1], g.dims[2]}}; }

class NeighborGrid {
 public:
  // Bins particles into cells; afterwards sorted_order() lists particles cell by cell.
  void bin(const real* x, const real* y, const real* z, std::size_t n, const Domain& domain, double h);
  // The same over the cells `range` of `geometry`, which must hold every particle's cell (a
  // rank of a distributed run bins its own particles and its ghosts in the cells they cover);
  // with a `key`, the particles of each cell ordered by it, as order_cells_by does (in the
  // same parallel region).
  void bin(const real* x, const real* y, const real* z, std::size_t n, const GridGeometry& geometry,
           const CellRange& range, const std::int64_t* key = nullptr);
  // Orders the particles of each cell by `key` (ascending, keys distinct) in sorted_order().
  void order_cells_by(const std::int64_t* key);
  // Builds the lists of neighbours j != i with |x_i - x_j|^2 < h^2 of the particles i < listed
  // (all of them by default; a rank lists its own particles, whose neighbours include ghosts).
  void build_lists(const real* x, const real* y, const real* z, double h, std::size_t listed = SIZE_MAX);
  // Adds `by` to every index below `below` in the lists: they then name the particles'
  // copies placed `by` further on (Simulation::set_check_ghosts).
  void offset_neighbors(std::uint32_t below, std::uint32_t by);

  // The lists are followed by this many valid indices (0), so that a vector loop may load a
  // whole vector of indices past the end of a list and mask the extra lanes.
  static constexpr std::size_t kListPadding = 64;

  std::span<const std::uint32_t> sorted_order() const { return {sorted_.data(), cell_.size()}; }
  const std::uint32_t* neighbors(std::size_t i) const { return list_.data() + offset_[i]; }
  std::uint32_t count(std::size_t i) const { return static_cast<std::uint32_t>(offset_[i + 1] - offset_[i]); }
  std::size_t particle_count() const { return offset_.empty() ? 0 : offset_.size() - 1; }  // listed
  std::size_t binned_count() const { return cell_.size(); }

  // The prelude of every pair loop: calls visit(j, dx, dy, dz, r2) for each neighbour j of
  // particle i, in list order, with (dx, dy, dz) = x_i - x_j and r2 its squared length.
  // Inlined, it compiles to the loop written out by hand.
  template <class Visit>
  void for_each_neighbor(std::size_t i, const real* x, const real* y, const real* z, Visit&& visit) const {
    const std::uint32_t* nb = neighbors(i);
    for (std::uint32_t k = 0; k < count(i); ++k) {
      const std::uint32_t j = nb[k];
      const real dx = x[i] - x[j], dy = y[i] - y[j], dz = z[i] - z[j];
      visit(j, dx, dy, dz, dx * dx + dy * dy + dz * dz);
    }
  }

  std::size_t cell_count() const { return cell_start_.empty() ? 0 : cell_start_.size() - 1; }
  // The binning: the whole domain's cells, the box of them binned (cells numbered x fastest
  // within it), and each binned cell's first slot in sorted_order() (cell_count() + 1 entries).
  const GridGeometry& geometry() const { return geometry_; }
  const CellRange& range() const { return range_; }
  const std::uint32_t* cell_starts() const { return cell_start_.data(); }
  double mean_neighbors() const;
  // Whether the last build_lists took one pass (the lists fitted where the build before said).
  bool built_in_one_pass() const { return one_pass_; }
  // The longest list of the last build.
  std::uint32_t max_neighbors() const { return most_; }

  // Largest number of cells of a domain's grid.
  static std::size_t max_cells();

 private:
  std::size_t cell_of(real x, real y, real z) const;
  void order_cell(std::size_t c, const std::int64_t* key);

  GridGeometry geometry_;
  CellRange range_;
  long dims_[3] = {1, 1, 1};  // of the range
  std::vector<std::uint32_t> cell_;         // cell of each particle
  std::vector<std::uint32_t> cell_start_;   // first sorted slot of each cell (ncells + 1)
  std::vector<std::uint32_t> sorted_;       // particle indices, cell by cell, and kListPadding zeros
  std::vector<real> packed_[3];             // positions in sorted_ order, padded
  std::vector<std::vector<std::uint32_t>> histogram_;  // per thread, per cell
  std::vector<std::uint32_t> cells_counted_;           // per thread: the particles in its range of cells
  std::vector<std::uint32_t> offset_;       // list of particle i: list_[offset_[i] .. offset_[i+1])
  std::vector<std::uint32_t> list_;         // and kListPadding zeros after the last
  // The one-pass build (build_lists): pairs per block of kBlock particles at the last build,
  // and this build's segments and their use.
  static constexpr std::size_t kBlock = 1024;
  bool fill_in_one_pass(const CellSearch& search, bool& packed);
  void fill_in_two_passes(const CellSearch& search);
  void pack(const CellSearch& search, std::size_t slot);
  std::vector<std::uint64_t> block_pairs_, segment_, used_;
  std::vector<std::uint32_t> block_most_;  // the longest list of each block
  bool one_pass_ = false;
  std::uint32_t most_ = 0;  // the longest list
};

}  // namespace pbf
