#pragma once
// Particles near arbitrary points (probes, gauges): a grid of cells at least h wide, built
// when a measurement asks for it and thrown away afterwards, so a scene without probes pays
// nothing. The engine's NeighborGrid answers "neighbours of particle i" from lists built once
// per step; a probe point is no particle, and its grid is private, hence this small one.
//
// The visit order is fixed (the 3 x 3 x 3 cells around the point in z, y, x order, ascending
// particle index within a cell: a serial counting sort), so a sum over it has the same bits
// at any thread count, and queries of different points may run in parallel.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "engine/core/domain.hpp"
#include "engine/core/real.hpp"
#include "engine/registry/params.hpp"

namespace pbf {

class Simulation;

class PointQuery {
 public:
  // Bins n particles into cells at least h wide over the domain (positions outside it fall
  // into the edge cells, as in NeighborGrid; the cell count is capped the same way).
  PointQuery(const real* x, const real* y, const real* z, std::size_t n, const Domain& domain, double h);

  // Calls visit(j, dx, dy, dz, r2) for every particle j with r2 = |p - x_j|^2 < h^2, where
  // (dx, dy, dz) = p - x_j, in the fixed order above.
  template <class Visit>
  void for_each_near(double px, double py, double pz, Visit&& visit) const {
    long from[3], to[3];
    const double p[3] = {px, py, pz};
    for (int a = 0; a < 3; ++a) {
      from[a] = cell_along(a, p[a] - h_);
      to[a] = cell_along(a, p[a] + h_);
    }
    for (long cz = from[2]; cz <= to[2]; ++cz)
      for (long cy = from[1]; cy <= to[1]; ++cy) {
        // Cells are numbered x fastest: a row of cells along x is one run of the sorted order.
        const std::size_t row = static_cast<std::size_t>((cz * dims_[1] + cy) * dims_[0]);
        for (std::uint32_t s = start_[row + from[0]]; s < start_[row + to[0] + 1]; ++s) {
          const std::uint32_t j = sorted_[s];
          const double dx = px - double(x_[j]), dy = py - double(y_[j]), dz = pz - double(z_[j]);
          const double r2 = dx * dx + dy * dy + dz * dz;
          if (r2 < h2_) visit(j, dx, dy, dz, r2);
        }
      }
  }

 private:
  long cell_along(int axis, double coordinate) const;

  const real *x_, *y_, *z_;
  double h_, h2_;
  double lo_[3] = {0, 0, 0};
  double cell_size_ = 1;
  long dims_[3] = {1, 1, 1};
  std::vector<std::uint32_t> start_;   // first sorted slot of each cell (cells + 1)
  std::vector<std::uint32_t> sorted_;  // particle indices, cell by cell, ascending within a cell
};

// What the probe and gauge styles share about their points.
// Throws unless every point lies inside the domain (a probe outside it would read nothing,
// silently): "WHAT: parameter 'points': point K (x, y, z) is outside the domain ...".
void check_points_inside(const Points& points, const Domain& domain, const std::string& what);
// Refuses an empty point list, and labels that do not give one name per point, repeat a name,
// or use characters other than letters, digits, '_' and '-' (a label is a CSV column and a
// thermo name). With `p` lacking "labels": "1".."N".
std::vector<std::string> point_labels(const Params& p, std::size_t points);
// Whether a compute of the simulation samples the "pressure" field (a probe with field
// "pressure"): pbf keeps that field only then (engine/computes/probe.cpp).
bool computes_read_pressure(const Simulation& sim);

}  // namespace pbf
