// Exact signed distances of the primitives (Quilez's box and capped-cylinder forms), evaluated
// in the primitive's own frame: a point is taken back through the placement, and the distance
// scaled back up (a uniform scale keeps distances proportional; a primitive refuses any other).
#include "engine/geometry/shape.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/core/error.hpp"
#include "engine/geometry/mesh_file.hpp"
#include <fmt/format.h>

namespace pbf {

namespace {

double dot(const Point& a, const Point& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double length(const Point& a) { return std::sqrt(dot(a, a)); }

// A shape defined in its own frame.
class PlacedShape : public Shape {
 public:
  explicit PlacedShape(const Placement& p) : placement_(p), rotation_(rotation_matrix(p.rotate_deg)) {
    if (!(p.scale[0] > 0) || p.scale[1] != p.scale[0] || p.scale[2] != p.scale[0])
      throw Error(fmt::format("a primitive takes one positive scale for all three axes (its size comes from its own "
                              "parameters), got {{{}, {}, {}}}",
                              p.scale[0], p.scale[1], p.scale[2]));
  }
  double signed_distance(const Point& p) const final {
    const Point d{p[0] - placement_.translate[0], p[1] - placement_.translate[1], p[2] - placement_.translate[2]};
    Point local;  // R^T d / scale
    for (int a = 0; a < 3; ++a)
      local[a] = (rotation_[a] * d[0] + rotation_[3 + a] * d[1] + rotation_[6 + a] * d[2]) / placement_.scale[0];
    return placement_.scale[0] * local_distance(local);
  }
  double reach() const final { return std::numeric_limits<double>::infinity(); }

 private:
  virtual double local_distance(const Point& p) const = 0;
  Placement placement_;
  std::array<double, 9> rotation_;
};

class Box final : public PlacedShape {
 public:
  Box(const Point& lo, const Point& hi, const Placement& p) : PlacedShape(p) {
    for (int a = 0; a < 3; ++a) {
      center_[a] = 0.5 * (lo[a] + hi[a]);
      half_[a] = 0.5 * (hi[a] - lo[a]);
    }
  }

 private:
  double local_distance(const Point& p) const override {
    Point q, outside;
    for (int a = 0; a < 3; ++a) {
      q[a] = std::abs(p[a] - center_[a]) - half_[a];
      outside[a] = std::max(q[a], 0.0);
    }
    return length(outside) + std::min(std::max(q[0], std::max(q[1], q[2])), 0.0);
  }
  Point center_, half_;
};

class Sphere final : public PlacedShape {
 public:
  Sphere(const Point& c, double r, const Placement& p) : PlacedShape(p), center_(c), radius_(r) {}

 private:
  double local_distance(const Point& p) const override {
    return length({p[0] - center_[0], p[1] - center_[1], p[2] - center_[2]}) - radius_;
  }
  Point center_;
  double radius_;
};

class Cylinder final : public PlacedShape {
 public:
  Cylinder(const Point& base, const Point& top, double r, const Placement& p) : PlacedShape(p), radius_(r) {
    for (int a = 0; a < 3; ++a) center_[a] = 0.5 * (base[a] + top[a]);
    const Point axis{top[0] - base[0], top[1] - base[1], top[2] - base[2]};
    half_length_ = 0.5 * length(axis);
    for (int a = 0; a < 3; ++a) axis_[a] = axis[a] / (2 * half_length_);
  }

 private:
  double local_distance(const Point& p) const override {
    const Point d{p[0] - center_[0], p[1] - center_[1], p[2] - center_[2]};
    const double along = dot(d, axis_);
    const double across = std::sqrt(std::max(dot(d, d) - along * along, 0.0));
    const double qr = across - radius_, qa = std::abs(along) - half_length_;
    return std::hypot(std::max(qr, 0.0), std::max(qa, 0.0)) + std::min(std::max(qr, qa), 0.0);
  }
  Point center_, axis_;
  double radius_, half_length_;
};

class Plane final : public PlacedShape {
 public:
  Plane(const Point& point, const Point& normal, const Placement& p) : PlacedShape(p), point_(point) {
    const double n = length(normal);
    for (int a = 0; a < 3; ++a) normal_[a] = normal[a] / n;
  }

 private:
  double local_distance(const Point& p) const override {
    return dot({p[0] - point_[0], p[1] - point_[1], p[2] - point_[2]}, normal_);
  }
  Point point_, normal_;
};

}  // namespace

std::unique_ptr<Shape> box_shape(const Point& lo, const Point& hi, const Placement& placement) {
  return std::make_unique<Box>(lo, hi, placement);
}
std::unique_ptr<Shape> sphere_shape(const Point& center, double radius, const Placement& placement) {
  return std::make_unique<Sphere>(center, radius, placement);
}
std::unique_ptr<Shape> cylinder_shape(const Point& base, const Point& top, double radius, const Placement& placement) {
  return std::make_unique<Cylinder>(base, top, radius, placement);
}
std::unique_ptr<Shape> plane_shape(const Point& point, const Point& normal, const Placement& placement) {
  return std::make_unique<Plane>(point, normal, placement);
}

}  // namespace pbf
