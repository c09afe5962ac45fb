#include "engine/sph/point_query.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <set>

#include "engine/core/error.hpp"

#include "engine/sph/neighbor_grid.hpp"

namespace pbf {

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
