#include "engine/geometry/motion.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "engine/core/error.hpp"
#include "engine/geometry/mesh_file.hpp"

namespace pbf {

void check_pose(const Pose& pose, const std::string& what) {
  for (int c = 0; c < 6; ++c) {
    const double v = c < 3 ? pose.translate[c] : pose.rotate_deg[c - 3];
    if (!std::isfinite(v) || std::abs(v) > 1e6)
      throw Error(fmt::format("{} returned {}[{}] = {}: a pose needs finite numbers of magnitude at most 1e6", what,
                              c < 3 ? "translate" : "rotate", c % 3 + 1, std::isnan(v) ? "nan" : fmt::format("{}", v)));
  }
}

namespace {

// The pose's six numbers, so interpolation is one loop.
std::array<double, 6> numbers(const Pose& p) {
  return {p.translate[0], p.translate[1], p.translate[2], p.rotate_deg[0], p.rotate_deg[1], p.rotate_deg[2]};
}
Pose pose_of(const std::array<double, 6>& v) { return Pose{{v[0], v[1], v[2]}, {v[3], v[4], v[5]}}; }

}  // namespace

Keyframes::Keyframes(std::vector<Key> keys, Interpolation interpolation, const std::string& what)
    : keys_(std::move(keys)), interpolation_(interpolation) {
  if (keys_.empty()) throw Error(fmt::format("{}: needs at least one key", what));
  for (std::size_t k = 0; k < keys_.size(); ++k) {
    bool finite = std::isfinite(keys_[k].t);
    for (double v : numbers(keys_[k].pose)) finite = finite && std::isfinite(v) && std::abs(v) <= 1e6;
    if (!finite) throw Error(fmt::format("{}: key {} must hold finite numbers of magnitude at most 1e6", what, k + 1));
    if (k > 0 && !(keys_[k].t > keys_[k - 1].t))
      throw Error(fmt::format("{}: key {} (t = {}) is not after key {} (t = {}): key times must increase", what, k + 1,
                              keys_[k].t, k, keys_[k - 1].t));
  }
}

Pose Keyframes::at(double t) const {
  if (t <= keys_.front().t) return keys_.front().pose;
  if (t >= keys_.back().t) return keys_.back().pose;
  const std::size_t k = static_cast<std::size_t>(
      std::upper_bound(keys_.begin(), keys_.end(), t, [](double v, const Key& key) { return v < key.t; }) -
      keys_.begin() - 1);
  const double t0 = keys_[k].t, t1 = keys_[k + 1].t, span = t1 - t0, s = (t - t0) / span;
  const auto p0 = numbers(keys_[k].pose), p1 = numbers(keys_[k + 1].pose);
  std::array<double, 6> out{};
  if (interpolation_ == Interpolation::linear) {
    for (int c = 0; c < 6; ++c) out[c] = p0[c] + s * (p1[c] - p0[c]);
    return pose_of(out);
  }
  // Cubic Hermite with Catmull-Rom tangents (p[k+1] - p[k-1]) / (t[k+1] - t[k-1]); zero at the
  // first and last key, where the solid comes from and goes to rest.
  auto tangent = [&](std::size_t j, int c) {
    if (j == 0 || j + 1 == keys_.size()) return 0.0;
    return (numbers(keys_[j + 1].pose)[c] - numbers(keys_[j - 1].pose)[c]) / (keys_[j + 1].t - keys_[j - 1].t);
  };
  const double h00 = (1 + 2 * s) * (1 - s) * (1 - s), h10 = s * (1 - s) * (1 - s), h01 = s * s * (3 - 2 * s),
               h11 = s * s * (s - 1);
  for (int c = 0; c < 6; ++c) out[c] = h00 * p0[c] + h10 * span * tangent(k, c) + h01 * p1[c] + h11 * span * tangent(k + 1, c);
  return pose_of(out);
}

std::string Keyframes::description() const {
  return fmt::format("{} keyframes from t = {} to {} ({})", keys_.size(), keys_.front().t, keys_.back().t,
                     interpolation_ == Interpolation::linear ? "linear" : "spline");
}

Point RigidTransform::apply(const Point& x) const {
  const Point r = rotate(x);
  return {r[0] + c[0], r[1] + c[1], r[2] + c[2]};
}

Point RigidTransform::apply_inverse(const Point& x) const { return rotate_inverse({x[0] - c[0], x[1] - c[1], x[2] - c[2]}); }

Point RigidTransform::rotate(const Point& v) const {
  return {R[0] * v[0] + R[1] * v[1] + R[2] * v[2], R[3] * v[0] + R[4] * v[1] + R[5] * v[2],
          R[6] * v[0] + R[7] * v[1] + R[8] * v[2]};
}

Point RigidTransform::rotate_inverse(const Point& v) const {
  return {R[0] * v[0] + R[3] * v[1] + R[6] * v[2], R[1] * v[0] + R[4] * v[1] + R[7] * v[2],
          R[2] * v[0] + R[5] * v[1] + R[8] * v[2]};
}

bool RigidTransform::identity() const { return *this == RigidTransform{}; }

RigidTransform transform_of(const Pose& pose, const Point& pivot) {
  RigidTransform T;
  T.R = rotation_matrix(pose.rotate_deg);
  const Point r = T.rotate(pivot);
  for (int a = 0; a < 3; ++a) T.c[a] = pivot[a] - r[a] + pose.translate[a];
  return T;
}

}  // namespace pbf
