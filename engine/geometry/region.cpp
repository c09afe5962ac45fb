#include "engine/geometry/region.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <string>

#include "engine/core/error.hpp"
#include "engine/core/simulation.hpp"

namespace pbf {

std::vector<ParamSpec> Region::params() {
  return {ParamSpec{"region", ParamType::String, std::nullopt, "",
                    "the region: \"box\" (lo, hi), \"sphere\" (center, radius), \"half_space\" (point, normal: the "
                    "side the normal points to) or \"solid\" (solid: inside that solid's wall)"}
              .one_of({"box", "sphere", "half_space", "solid"}),
          ParamSpec{"lo", ParamType::Vector3, std::nullopt, "m", "box: lower corner", true}.magnitude_at_most(1e6),
          ParamSpec{"hi", ParamType::Vector3, std::nullopt, "m", "box: upper corner", true}.magnitude_at_most(1e6),
          ParamSpec{"center", ParamType::Vector3, std::nullopt, "m", "sphere: centre", true}.magnitude_at_most(1e6),
          ParamSpec{"radius", ParamType::Real, std::nullopt, "m", "sphere: radius", true}.above_within(0, 1e6),
          ParamSpec{"point", ParamType::Vector3, std::nullopt, "m", "half_space: a point on its plane", true}
              .magnitude_at_most(1e6),
          ParamSpec{"normal", ParamType::Vector3, std::nullopt, "",
                    "half_space: the plane's normal, pointing into the region (any length)", true}
              .magnitude_at_most(1e6),
          ParamSpec{"solid", ParamType::String, std::nullopt, "", "solid: the id of a solid fix at rest", true}};
}

Region::Region(const Params& p) {
  const std::string& shape = p.string("region");
  const std::vector<std::string> needs = shape == "box"      ? std::vector<std::string>{"lo", "hi"}
                                         : shape == "sphere" ? std::vector<std::string>{"center", "radius"}
                                         : shape == "half_space" ? std::vector<std::string>{"point", "normal"}
                                                                 : std::vector<std::string>{"solid"};
  for (const char* name : {"lo", "hi", "center", "radius", "point", "normal", "solid"}) {
    const bool needed = std::find(needs.begin(), needs.end(), std::string(name)) != needs.end();
    if (needed && !p.has(name))
      throw Error(fmt::format("parameter '{}' is missing: region \"{}\" needs {}", name, shape, fmt::join(needs, " and ")));
    if (!needed && p.has(name))
      throw Error(fmt::format("parameter '{}' does not apply to region \"{}\" (it takes {})", name, shape,
                              fmt::join(needs, " and ")));
  }
  if (shape == "box") {
    shape_ = Shape::box;
    a_ = p.vec3("lo");
    b_ = p.vec3("hi");
    for (int k = 0; k < 3; ++k)
      if (!(b_[k] > a_[k]))
        throw Error(fmt::format("parameters 'lo' and 'hi': the box is empty along {} ({} to {})", "xyz"[k], a_[k], b_[k]));
  } else if (shape == "sphere") {
    shape_ = Shape::sphere;
    a_ = p.vec3("center");
    b_ = {p.real("radius"), 0, 0};
  } else if (shape == "half_space") {
    shape_ = Shape::half_space;
    a_ = p.vec3("point");
    const Vec3 n = p.vec3("normal");
    const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(length > 0)) throw Error("parameter 'normal' is the zero vector: a plane needs a direction");
    b_ = {n[0] / length, n[1] / length, n[2] / length};
  } else {
    shape_ = Shape::solid;
    solid_id_ = p.string("solid");
  }
}

void Region::check_scene(const Simulation& sim) {
  if (shape_ != Shape::solid) return;
  solid_ = nullptr;
  std::vector<std::string> names;
  for (const SolidBody* s : sim.solid_bodies()) {
    names.push_back(s->name());
    if (s->name() == solid_id_) solid_ = s;
  }
  if (!solid_)
    throw Error(fmt::format("parameter 'solid': no solid '{}' in the pipeline (solids: {})", solid_id_,
                            names.empty() ? "none" : fmt::format("{}", fmt::join(names, ", "))));
  if (!solid_->depth_in_wall({0, 0, 0}))
    throw Error(fmt::format("parameter 'solid': solid '{}' moves, or no run has built its map yet: a region inside "
                            "it needs a solid at rest, after a run",
                            solid_id_));
}

bool Region::contains(const real q[3]) const {
  const double x = q[0], y = q[1], z = q[2];
  switch (shape_) {
    case Shape::box:
      return x >= a_[0] && x <= b_[0] && y >= a_[1] && y <= b_[1] && z >= a_[2] && z <= b_[2];
    case Shape::sphere: {
      const double dx = x - a_[0], dy = y - a_[1], dz = z - a_[2];
      return dx * dx + dy * dy + dz * dz <= b_[0] * b_[0];
    }
    case Shape::half_space:
      return (x - a_[0]) * b_[0] + (y - a_[1]) * b_[1] + (z - a_[2]) * b_[2] > 0;
    case Shape::solid: {
      const auto depth = solid_->depth_in_wall({x, y, z});
      return depth && *depth > 0;
    }
  }
  return false;
}

std::size_t Region::mark_inside(const Simulation& sim, std::vector<char>& drop) const {
  const auto& P = sim.particles();
  drop.assign(P.size(), 0);
  std::size_t inside = 0;
#pragma omp parallel for schedule(static) reduction(+ : inside)
  for (std::size_t i = 0; i < P.size(); ++i) {
    const real q[3] = {P.x()[i], P.y()[i], P.z()[i]};
    drop[i] = contains(q);
    inside += drop[i];
  }
  return inside;
}

std::string Region::describe() const {
  switch (shape_) {
    case Shape::box:
      return fmt::format("box [{}, {}] x [{}, {}] x [{}, {}]", a_[0], b_[0], a_[1], b_[1], a_[2], b_[2]);
    case Shape::sphere:
      return fmt::format("sphere of radius {} about ({}, {}, {})", b_[0], a_[0], a_[1], a_[2]);
    case Shape::half_space:
      return fmt::format("half-space beyond ({}, {}, {}) along ({:.4g}, {:.4g}, {:.4g})", a_[0], a_[1], a_[2], b_[0],
                         b_[1], b_[2]);
    case Shape::solid:
      return fmt::format("inside solid '{}'", solid_id_);
  }
  return "";
}

}  // namespace pbf
