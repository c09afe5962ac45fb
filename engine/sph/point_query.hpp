#pragma once
// Particles near arbitrary points (probes, gauges), over a binned NeighborGrid: the
// simulation's point grid (Simulation::point_cells), binned when a measurement asks for it, so
// a scene without probes pays nothing. The engine's neighbour lists answer "neighbours of
// particle i"; a probe point is no particle, hence this walk over the cells around it.
//
// The visit order is fixed: the cells around the point in z, y, x order, ascending particle
// id within a cell. A sum over it has the same bits at any thread count, and on any rank of
// a distributed run whose particles and ghosts cover the point's neighbourhood.
#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "engine/core/real.hpp"
#include "engine/sph/neighbor_grid.hpp"

namespace pbf {

class Simulation;

class PointQuery {
 public:
  // `grid` binned (and ordered by id) over these positions; h the search radius.
  PointQuery(const NeighborGrid& grid, const real* x, const real* y, const real* z, double h)
      : grid_(grid), x_(x), y_(y), z_(z), h_(h), h2_(h * h) {}

  // Calls visit(j, dx, dy, dz, r2) for every particle j with r2 = |p - x_j|^2 < h^2, where
  // (dx, dy, dz) = p - x_j, in the fixed order above.
  template <class Visit>
  void for_each_near(double px, double py, double pz, Visit&& visit) const {
    const GridGeometry& g = grid_.geometry();
    const CellRange& range = grid_.range();
    long from[3], to[3], dims[3];
    const double p[3] = {px, py, pz};
    for (int a = 0; a < 3; ++a) {
      dims[a] = std::max(1L, range.hi[a] - range.lo[a]);
      from[a] = std::max(g.cell_along(a, p[a] - h_), range.lo[a]) - range.lo[a];
      to[a] = std::min(g.cell_along(a, p[a] + h_), range.hi[a] - 1) - range.lo[a];
    }
    const std::uint32_t* start = grid_.cell_starts();
    const std::uint32_t* sorted = grid_.sorted_order().data();
    for (long cz = from[2]; cz <= to[2]; ++cz)
      for (long cy = from[1]; cy <= to[1]; ++cy) {
        // Cells are numbered x fastest: a row of cells along x is one run of the sorted order.
        const std::size_t row = static_cast<std::size_t>((cz * dims[1] + cy) * dims[0]);
        for (std::uint32_t s = start[row + from[0]]; s < start[row + to[0] + 1]; ++s) {
          const std::uint32_t j = sorted[s];
          const double dx = px - double(x_[j]), dy = py - double(y_[j]), dz = pz - double(z_[j]);
          const double r2 = dx * dx + dy * dy + dz * dz;
          if (r2 < h2_) visit(j, dx, dy, dz, r2);
        }
      }
  }

 private:
  const NeighborGrid& grid_;
  const real *x_, *y_, *z_;
  double h_, h2_;
};

// Whether a compute of the simulation samples the "pressure" field (a probe with field
// "pressure"): pbf keeps that field only then (engine/computes/probe.cpp).
bool computes_read_pressure(const Simulation& sim);

}  // namespace pbf
