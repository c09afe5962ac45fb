#include "engine/sph/point_query.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <set>

#include "engine/core/error.hpp"

#include "engine/sph/neighbor_grid.hpp"

namespace pbf {

PointQuery::PointQuery(const real* x, const real* y, const real* z, std::size_t n, const Domain& domain, double h)
    : x_(x), y_(y), z_(z), h_(h), h2_(h * h) {
  if (!(h > 0)) throw Error("the kernel radius h is not set (pbf.kernel_radius): a probe has no kernel");
  // Cells at least h wide, widened while the box would need more than the neighbour grid's
  // cap (memory follows the particle count, not the box volume over h^3).
  cell_size_ = h;
  const double cap = static_cast<double>(NeighborGrid::max_cells(n));
  auto cells_along = [&](int a) { return std::max(1.0, std::ceil(domain.extent(a) / cell_size_)); };
  for (;;) {
    const double total = cells_along(0) * cells_along(1) * cells_along(2);
    if (total <= cap) break;
    cell_size_ *= std::max(1.01, std::cbrt(total / cap));
  }
  for (int a = 0; a < 3; ++a) dims_[a] = static_cast<long>(cells_along(a)), lo_[a] = domain.lo[a];
  const std::size_t cells = static_cast<std::size_t>(dims_[0] * dims_[1] * dims_[2]);

  // A serial counting sort: O(n), done only when a probe is evaluated, and its order
  // (ascending index within a cell) does not depend on the thread count.
  std::vector<std::uint32_t> cell(n);
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    const long cx = cell_along(0, x[i]), cy = cell_along(1, y[i]), cz = cell_along(2, z[i]);
    cell[i] = static_cast<std::uint32_t>((cz * dims_[1] + cy) * dims_[0] + cx);
  }
  start_.assign(cells + 1, 0);
  for (std::size_t i = 0; i < n; ++i) ++start_[cell[i] + 1];
  for (std::size_t c = 0; c < cells; ++c) start_[c + 1] += start_[c];
  sorted_.resize(n);
  std::vector<std::uint32_t> next(start_.begin(), start_.end() - 1);
  for (std::size_t i = 0; i < n; ++i) sorted_[next[cell[i]]++] = static_cast<std::uint32_t>(i);
}

long PointQuery::cell_along(int axis, double coordinate) const {
  const double c = std::floor((coordinate - lo_[axis]) / cell_size_);
  if (!(c >= 0)) return 0;  // also NaN
  return c >= static_cast<double>(dims_[axis]) ? dims_[axis] - 1 : static_cast<long>(c);
}

void check_points_inside(const Points& points, const Domain& domain, const std::string& what) {
  for (std::size_t k = 0; k < points.size(); ++k) {
    const auto& q = points[k];
    bool inside = true;
    for (int a = 0; a < 3; ++a) inside = inside && q[a] >= domain.lo[a] && q[a] <= domain.hi[a];
    if (!inside)
      throw Error(fmt::format("{}: parameter 'points': point {} ({}, {}, {}) is outside the domain ({}, {}, {}) to "
                              "({}, {}, {})",
                              what, k + 1, q[0], q[1], q[2], domain.lo[0], domain.lo[1], domain.lo[2], domain.hi[0],
                              domain.hi[1], domain.hi[2]));
  }
}

std::vector<std::string> point_labels(const Params& p, std::size_t points) {
  if (points == 0) throw Error("parameter 'points': give at least one point, {{x, y, z}, ...}");
  std::vector<std::string> labels;
  if (!p.has("labels")) {
    for (std::size_t k = 1; k <= points; ++k) labels.push_back(std::to_string(k));
    return labels;
  }
  labels = p.names("labels");
  if (labels.size() != points)
    throw Error(fmt::format("parameter 'labels': {} label{} for {} point{} (give one per point)", labels.size(),
                            labels.size() == 1 ? "" : "s", points, points == 1 ? "" : "s"));
  std::set<std::string> seen;
  for (const auto& label : labels) {
    const bool plain = !label.empty() && std::all_of(label.begin(), label.end(), [](char c) {
      return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
    });
    if (!plain)
      throw Error(fmt::format("parameter 'labels': '{}' is not a plain name (letters, digits, '_' and '-': it "
                              "names a CSV column and a thermo value)",
                              label));
    if (!seen.insert(label).second) throw Error(fmt::format("parameter 'labels': '{}' is given twice", label));
  }
  return labels;
}

}  // namespace pbf
