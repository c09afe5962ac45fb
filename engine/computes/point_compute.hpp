#pragma once
// What the probe and gauge styles share: points with labels, checked against the scene. A
// point outside the domain is refused (it would read nothing); one deep inside a solid at
// rest is warned about (no particle ever comes near it).
#include <cstddef>
#include <set>
#include <string>
#include <vector>

#include "engine/core/compute.hpp"
#include "engine/core/domain.hpp"
#include "engine/registry/params.hpp"

namespace pbf {

class PointCompute : public Compute {
 public:
  // Reads `points` and `labels`. Refuses an empty point list, and labels that do not give one
  // name per point, repeat a name, or use characters other than letters, digits, '_' and '-'
  // (a label is a CSV column and a thermo name).
  PointCompute(const std::string& id, const std::string& style, const Params& p);

  // A label names its value even alone: a probe of one point labelled "floor" is "p.floor".
  bool names_single_value() const override { return labelled_; }
  void check_scene(const Simulation& sim) override;

 protected:
  // Throws unless every point lies inside the domain: "compute 'ID' (STYLE): parameter
  // 'points': point K (x, y, z) is outside the domain (lo) to (hi)".
  void check_inside(const Domain& domain) const;
  // What a point deep inside a solid reads, ending the warning about it.
  virtual const char* inside_solid_reads() const = 0;

  Points points_;
  std::vector<std::string> labels_;  // "1".."N" without `labels`
  bool labelled_;

 private:
  // How messages name point k: "point 2 (x, y, z)", or with labels "point 'floor' (x, y, z)".
  std::string point_name(std::size_t k) const;

  std::set<std::string> warned_;  // "SOLID POINT" pairs warned about already: once each
};

}  // namespace pbf
