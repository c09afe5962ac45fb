#pragma once
// A region of space whose particles are removed: by the `outflow` fix every step, by
// pbf.delete once. A box (lo <= x <= hi), a sphere (|x - center| <= radius), the half-space
// beyond a plane ((x - point) . normal > 0: the side the normal points to), or the inside of
// a solid (behind its surface, in the wall, where the solid stands now).
#include <string>
#include <vector>

#include "engine/core/real.hpp"
#include "engine/registry/params.hpp"

namespace pbf {

class Simulation;
class SolidBody;

class Region {
 public:
  // The parameters that say a region (`region` and those its shape needs), for a schema.
  static std::vector<ParamSpec> params();
  // From checked parameters; throws naming the parameter a shape lacks or has too many of.
  explicit Region(const Params& p);

  // Finds the solid of a solid region in the scene: a solid at rest whose map a run has built.
  void check_scene(const Simulation& sim);
  // Marks this rank's particles inside (drop[i] = 1); returns how many.
  std::size_t mark_inside(const Simulation& sim, std::vector<char>& drop) const;
  // Whether the point lies inside.
  bool contains(const real q[3]) const;
  // "box [lo, hi]", "sphere ...", for messages.
  std::string describe() const;

 private:
  enum class Shape { box, sphere, half_space, solid };
  Shape shape_;
  Vec3 a_{}, b_{};  // box: lo, hi; sphere: center, (radius, 0, 0); half_space: point, unit normal
  std::string solid_id_;
  const SolidBody* solid_ = nullptr;
};

}  // namespace pbf
