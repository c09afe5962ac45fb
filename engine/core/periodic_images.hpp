#pragma once
// Periodic images: along a periodic axis of the domain, particle j is also at x_j +/- L
// (Domain::image). The images a rank needs are ghosts, after its particles (and the other
// ranks' ghosts) in every array, with their owner's id and every field's value, the position
// shifted. So the neighbour search finds pairs across the faces in the cells beyond them
// (GridGeometry: along a periodic axis the cells tile the period and are not clamped), the
// pair loops need nothing of their own (x_i - x_j is the offset to the image), and a pass
// refreshes images through the same update_ghosts as the other ranks' ghosts.
//
// Which images: those whose cell lies in the cells the rank's grid covers (its particles'
// cells, or its box, grown by one cell): a particle's neighbours all lie in the 27 cells
// around its own, so every image within h of a particle is there. An image's cell comes from
// its shifted position, the same on every rank, and lists order a cell's particles by id: a
// period of at least two cells keeps a particle and its images in different cells, so the
// ids within a cell are distinct and the lists do not depend on the rank count.
//
// A distributed run's images of other ranks' particles come from them with the ghosts
// (engine/distributed/decomposition.cpp, by the same rule); these are a rank's images of its
// own particles, and in one process all of them. A scene without a periodic axis has none
// and pays nothing.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "engine/core/domain.hpp"
#include "engine/core/particles.hpp"
#include "engine/sph/neighbor_grid.hpp"

namespace pbf {

using Shift = std::array<std::int8_t, 3>;  // periods along x, y, z: -1, 0 or 1

// The shifts of the images along the periodic axes of `domain` (none when no axis is): 2, 8 or 26.
std::vector<Shift> image_shifts(const Domain& domain);
// Whether the cell of particle i's image `shift` away lies in `range`. Along an axis the
// shift leaves, the image's cell is the particle's own: `own_cell` (its 3 coordinates), or,
// without it, one `range` holds.
bool image_in(const Domain& domain, const GridGeometry& grid, const CellRange& range, const real* const x[3],
              std::size_t i, const Shift& shift, const long* own_cell = nullptr);

class PeriodicImages {
 public:
  // Appends as ghosts the images of the particles [0, P.size()) whose cells lie in `range`,
  // with every field's values (positions shifted). Ghosts already there stay.
  void build(Particles& P, const Domain& domain, const GridGeometry& grid, const CellRange& range);
  void clear() { owner_.clear(); shift_.clear(); }
  std::size_t count() const { return owner_.size(); }
  // Whether the images of the last build are still where it put them in P's arrays (the
  // ghosts are dropped when particles move to other ranks, are added or reordered).
  bool current(const Particles& P) const {
    return owner_.empty() || (P.ghosts() > 0 && first_ >= P.size() && first_ + owner_.size() <= P.size_with_ghosts());
  }
  // The images' copies of these arrays from their owners (one value per particle, ghosts included).
  void update(std::span<real* const> arrays) const;
  // The images' positions from their owners', shifted.
  void update_positions(const Domain& domain, real* const x[3]) const;

 private:
  std::size_t first_ = 0;             // index of the first image
  std::vector<std::uint32_t> owner_;  // of each image
  std::vector<Shift> shift_;
  std::vector<Shift> shifts_;         // the domain's (scratch)
};

}  // namespace pbf
