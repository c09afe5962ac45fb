#include "engine/computes/point_compute.hpp"

#include <algorithm>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "engine/core/error.hpp"
#include "engine/core/simulation.hpp"

namespace pbf {

namespace {

std::vector<std::string> read_labels(const Params& p, std::size_t points) {
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

}  // namespace

PointCompute::PointCompute(const std::string& id, const std::string& style, const Params& p)
    : Compute(id, style), points_(p.points("points")), labels_(read_labels(p, points_.size())),
      labelled_(p.has("labels")) {}

std::string PointCompute::point_name(std::size_t k) const {
  const auto& q = points_[k];
  const std::string label = labelled_ ? "'" + labels_[k] + "'" : labels_[k];
  return fmt::format("point {} ({}, {}, {})", label, q[0], q[1], q[2]);
}

void PointCompute::check_inside(const Domain& domain) const {
  for (std::size_t k = 0; k < points_.size(); ++k) {
    const auto& q = points_[k];
    bool inside = true;
    for (int a = 0; a < 3; ++a) inside = inside && q[a] >= domain.lo[a] && q[a] <= domain.hi[a];
    if (!inside)
      throw Error(fmt::format("compute '{}' ({}): parameter 'points': {} is outside the domain ({}, {}, {}) to "
                              "({}, {}, {})",
                              id(), style(), point_name(k), domain.lo[0], domain.lo[1], domain.lo[2], domain.hi[0],
                              domain.hi[1], domain.hi[2]));
  }
}

// A point more than a kernel radius inside a solid has no particle within h, ever (particles
// stay in front of the surface). One just behind the surface is a sensor on a wall: it reads
// the particles in front.
void PointCompute::check_scene(const Simulation& sim) {
  check_inside(sim.domain());
  for (const SolidBody* solid : sim.solid_bodies())
    for (std::size_t k = 0; k < points_.size(); ++k) {
      const auto depth = solid->depth_in_wall(points_[k]);
      if (!depth || !(*depth > sim.kernel_radius())) continue;
      if (!warned_.insert(solid->name() + " " + labels_[k]).second) continue;
      spdlog::warn("compute '{}' ({}): {} lies inside solid '{}', more than a kernel radius behind its surface, "
                   "where no particle comes: {}",
                   id(), style(), point_name(k), solid->name(), inside_solid_reads());
    }
}

}  // namespace pbf
