#pragma once
// Unit quaternions for a rigid body's orientation (w + x i + y j + z k): the rotation that takes
// a vector from the body's frame to the world's, v_world = q v_body q*.
#include <array>
#include <cmath>

namespace pbf {

struct Quaternion {
  double w = 1, x = 0, y = 0, z = 0;

  static Quaternion about_axis(int axis, double angle) {  // a coordinate axis 0, 1, 2
    Quaternion q{std::cos(0.5 * angle), 0, 0, 0};
    (axis == 0 ? q.x : axis == 1 ? q.y : q.z) = std::sin(0.5 * angle);
    return q;
  }
  static Quaternion about(const std::array<double, 3>& unit_axis, double angle) {  // any unit axis
    const double s = std::sin(0.5 * angle);
    return {std::cos(0.5 * angle), s * unit_axis[0], s * unit_axis[1], s * unit_axis[2]};
  }
  Quaternion operator*(const Quaternion& b) const {
    return {w * b.w - x * b.x - y * b.y - z * b.z, w * b.x + x * b.w + y * b.z - z * b.y,
            w * b.y - x * b.z + y * b.w + z * b.x, w * b.z + x * b.y - y * b.x + z * b.w};
  }
  Quaternion conjugate() const { return {w, -x, -y, -z}; }
  Quaternion normalized() const {
    const double n = std::sqrt(w * w + x * x + y * y + z * z);
    return {w / n, x / n, y / n, z / n};
  }
  // q v q*
  std::array<double, 3> rotate(const std::array<double, 3>& v) const {
    const Quaternion r = *this * Quaternion{0, v[0], v[1], v[2]} * conjugate();
    return {r.x, r.y, r.z};
  }
  // The rotation matrix (rows), v_world = M v_body.
  std::array<std::array<double, 3>, 3> matrix() const {
    return {{{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
             {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
             {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}}};
  }
  // From a proper rotation matrix (rows), by Shepperd's method (the largest of the four
  // candidates first, so no division by a small number).
  static Quaternion from_matrix(const std::array<std::array<double, 3>, 3>& m);
};

}  // namespace pbf
