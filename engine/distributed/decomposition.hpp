#pragma once
// Domain decomposition of a distributed run: each rank owns the particles in one box of the
// neighbour grid's cells, and holds copies (ghosts) of the other ranks' particles within one
// cell of its own, which its pair loops read as neighbours.
//
// Why the answer does not depend on the number of ranks: the cells are the whole domain's,
// the same on every rank (GridGeometry from the global particle count), and a list holds a
// particle's neighbours in cell order and then by id. A particle's neighbours all lie in the
// 27 cells around its own, and every particle of those cells is there, owned or ghost, so a
// rank lists exactly the neighbours a single process would, in the same order, and the pair
// sums over them have the same bits. Sums over particles are exact (ExactSum), hence
// independent of how the particles are shared.
//
// The boxes: recursive coordinate bisection over cells, each cut on a cell plane where the
// particle counts on either side are in proportion to the ranks on either side, from
// histograms summed over the ranks (integers: every rank computes the same tree). Cuts on
// cell planes make "within one cell" the halo; a library's (Zoltan's) cuts at arbitrary
// coordinates would not. Rebalanced when the largest rank holds more than `imbalance` times
// the mean.
//
// Particles move to the rank that owns their cell at the start of a step (with every field);
// ghosts are rebuilt at the neighbour stage from the predicted positions, between the ranks
// whose particles' cells come within one cell of each other, point to point, into buffers that
// keep their memory from step to step. update() refreshes the ghosts' copies of the arrays a
// pass is about to read at its neighbours.
//
// Along a periodic axis the ghosts include images (engine/core/periodic_images.hpp): a rank
// sends a peer its particle's image x + s L (s = -1, 0, 1 along each periodic axis, 0 for a
// plain ghost) when the image's cell lies within one cell of the peer's, by the rule a
// rank's own images follow, so every rank holds what one process holds near its particles.
// The sender shifts the positions it sends, at the build and at every refresh of positions.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "engine/core/domain.hpp"
#include "engine/core/particles.hpp"
#include "engine/core/periodic_images.hpp"
#include "engine/core/real.hpp"
#include "engine/sph/neighbor_grid.hpp"

namespace pbf {

// The box of cells that holds these particles (their first P.size()), clamped into the grid.
CellRange cells_holding(const Particles& P, const GridGeometry& grid);

class Decomposition {
 public:
  // Whether the run is split among ranks (more than one).
  static bool wanted();

  // Places the particles created since the last placement (each rank holds its share of them,
  // anywhere in the domain) on the ranks that own their cells; the first time, cuts the boxes.
  void distribute(Particles& P, const GridGeometry& grid);
  // Start of a step: particles outside this rank's box go to their owners (rebalancing first
  // when the imbalance has grown past the threshold).
  void migrate(Particles& P, const GridGeometry& grid);
  // Ghosts of the other ranks' particles within one cell of this rank's box or of its particles'
  // cells (at their current positions; a particle may have left the box since the step began),
  // so that the rank holds every particle near its own and near any point of its box (probes).
  // Returns the cells this rank's grid must cover.
  // With the images of the domain's periodic axes (not this rank's images of its own particles).
  CellRange build_ghosts(Particles& P, const GridGeometry& grid, const Domain& domain);
  // The ghosts' values of these arrays (one value per particle, ghosts included) from their
  // owners; `positions`: the arrays are x, y, z, shifted for images.
  void update(std::span<real* const> arrays, bool positions = false);

  // The rank whose box holds this cell.
  int owner(const long cell[3]) const;

  // Particles per rank at the last migration (min, mean, max), for the timing table.
  struct Load {
    double least = 0, mean = 0, most = 0;
  };
  const Load& load() const { return load_; }
  // Ghosts held after the last build, and their mean over the builds since the last reset.
  double ghosts_mean() const { return ghost_builds_ ? ghost_sum_ / double(ghost_builds_) : 0; }
  // Seconds spent communicating (ghosts, migration, updates) since the last reset.
  double seconds() const { return seconds_; }
  void reset_seconds() {
    seconds_ = 0;
    ghost_sum_ = 0;
    ghost_builds_ = 0;
  }

 private:
  struct Node {  // the bisection tree: a leaf names its rank
    int axis = -1;
    long at = 0;
    int below = -1, above = -1, rank = -1;
  };
  void balance(const Particles& P, const GridGeometry& grid, std::size_t counted);
  int split(int first_rank, int ranks, const CellRange& box, std::vector<std::uint32_t>& mine,
            const std::vector<long>& cells);
  void cells_of(const Particles& P, const GridGeometry& grid, std::size_t n);
  void send_away(Particles& P, const std::vector<int>& destination);
  void pack(const Particles& P, std::size_t i, std::vector<char>& out, const Shift& shift = {}) const;

  std::vector<Node> tree_;
  GridGeometry cut_for_;  // the cells the tree was cut in
  CellRange box_;  // this rank's box
  std::vector<long> cells_;  // 3 per particle: the cell coordinates (scratch)
  std::int64_t steps_since_balance_ = 0;
  Load load_;
  double seconds_ = 0, ghost_sum_ = 0;
  std::int64_t ghost_builds_ = 0;
  // The ghosts: per peer, the indices of this rank's particles it gets, and where its own land.
  std::vector<int> peers_;
  std::vector<std::vector<std::uint32_t>> send_index_;
  std::vector<std::vector<Shift>> send_shift_;  // the image each sends (0: the particle)
  Domain domain_;  // of the last ghost build
  std::vector<std::size_t> ghost_first_, ghost_count_;
  std::vector<std::vector<char>> send_, recv_;       // per peer (ghosts)
  std::vector<std::vector<char>> outgoing_, incoming_;  // per rank (migration)
  std::vector<FieldId> fields_;  // what a particle carries (every live field)
};

}  // namespace pbf
