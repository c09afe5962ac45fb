#pragma once
// A solid's shape as a signed distance: negative inside the closed surface, positive outside,
// |value| the distance to the surface (exact near it; beyond `reach()` only the sign counts).
// Primitives are analytic; a mesh samples a signed-distance grid (engine/geometry/mesh_sdf.hpp).
#include <array>
#include <memory>

#include "engine/geometry/triangle_mesh.hpp"

namespace pbf {

using Point = std::array<double, 3>;

class Shape {
 public:
  virtual ~Shape() = default;
  virtual double signed_distance(const Point& p) const = 0;
  // Up to which distance from the surface signed_distance() is a distance (infinite for
  // the primitives; a mesh grid's narrow band).
  virtual double reach() const = 0;
  // The cell size of the grid the distances are interpolated from (0: exact everywhere).
  virtual double grid_cell() const { return 0; }
};

// Primitives in their own frame, placed (scale, then rotation, then translation) in the world.
std::unique_ptr<Shape> box_shape(const Point& lo, const Point& hi, const Placement& placement);
std::unique_ptr<Shape> sphere_shape(const Point& center, double radius, const Placement& placement);
// A capped cylinder from the centre of its base to the centre of its top.
std::unique_ptr<Shape> cylinder_shape(const Point& base, const Point& top, double radius, const Placement& placement);
// The half-space behind a plane: `inside` is the side opposite to `normal`.
std::unique_ptr<Shape> plane_shape(const Point& point, const Point& normal, const Placement& placement);

}  // namespace pbf
