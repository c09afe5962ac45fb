#include "engine/bodies/quaternion.hpp"

namespace pbf {

Quaternion Quaternion::from_matrix(const std::array<std::array<double, 3>, 3>& m) {
  const double trace = m[0][0] + m[1][1] + m[2][2];
  Quaternion q;
  if (trace >= m[0][0] && trace >= m[1][1] && trace >= m[2][2]) {
    const double r = std::sqrt(1 + trace);
    q = {0.5 * r, (m[2][1] - m[1][2]) / (2 * r), (m[0][2] - m[2][0]) / (2 * r), (m[1][0] - m[0][1]) / (2 * r)};
  } else if (m[0][0] >= m[1][1] && m[0][0] >= m[2][2]) {
    const double r = std::sqrt(1 + m[0][0] - m[1][1] - m[2][2]);
    q = {(m[2][1] - m[1][2]) / (2 * r), 0.5 * r, (m[0][1] + m[1][0]) / (2 * r), (m[0][2] + m[2][0]) / (2 * r)};
  } else if (m[1][1] >= m[2][2]) {
    const double r = std::sqrt(1 - m[0][0] + m[1][1] - m[2][2]);
    q = {(m[0][2] - m[2][0]) / (2 * r), (m[0][1] + m[1][0]) / (2 * r), 0.5 * r, (m[1][2] + m[2][1]) / (2 * r)};
  } else {
    const double r = std::sqrt(1 - m[0][0] - m[1][1] + m[2][2]);
    q = {(m[1][0] - m[0][1]) / (2 * r), (m[0][2] + m[2][0]) / (2 * r), (m[1][2] + m[2][1]) / (2 * r), 0.5 * r};
  }
  return q.normalized();
}

}  // namespace pbf
