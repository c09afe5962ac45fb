#pragma once
// The image renderer's perspective camera and the small vector algebra it and the solids'
// rasteriser share. Internal to engine/render.
#include <algorithm>
#include <array>
#include <cmath>

#include "engine/core/domain.hpp"
#include "engine/render/image_renderer.hpp"

namespace pbf::render {

using Vec3 = std::array<double, 3>;
inline Vec3 sub(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double norm(const Vec3& a) { return std::sqrt(dot(a, a)); }
inline Vec3 scaled(const Vec3& a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }
inline bool finite(const Vec3& a) { return std::isfinite(a[0]) && std::isfinite(a[1]) && std::isfinite(a[2]); }
// a / |a| for any finite non-zero a: where |a|^2 would overflow or underflow (a camera 1e300 m
// away), a is first scaled by its largest component.
inline Vec3 unit(const Vec3& a) {
  const double n = norm(a);
  if (n > 0 && std::isfinite(n)) return scaled(a, 1 / n);
  const Vec3 b = scaled(a, 1 / std::max({std::fabs(a[0]), std::fabs(a[1]), std::fabs(a[2])}));
  return scaled(b, 1 / norm(b));
}

// Perspective camera: camera coordinates right, up and forward (the view direction).
struct Camera {
  Vec3 eye, right, up, forward;
  double focal;   // pixels per unit of (lateral offset / depth)
  double cx, cy;  // the image point on the view axis
  double near;    // nothing nearer than this is drawn
  double focus;   // the depth of the look-at point (on the view axis), where the scale bar is true

  // The camera of `spec` for the scene area (the image's left `scene_width` columns); throws
  // pbf::Error when it looks at its own position or along 'up'.
  Camera(const ImageSpec& spec, const Domain& domain, int scene_width);

  // Camera coordinates of a world point: lateral x, y and depth along the view direction.
  Vec3 to_camera(const Vec3& p) const {
    const Vec3 d = sub(p, eye);
    return {dot(d, right), dot(d, up), dot(d, forward)};
  }
  double screen_x(const Vec3& c) const { return cx + focal * c[0] / c[2]; }
  double screen_y(const Vec3& c) const { return cy - focal * c[1] / c[2]; }
};

}  // namespace pbf::render
