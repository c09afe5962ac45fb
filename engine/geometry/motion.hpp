#pragma once
// A solid's motion: its pose at time t, relative to where the scene placed it. The pose is a
// rotation about a pivot (degrees about x, then y, then z, the placement's convention)
// followed by a translation:
//   x(t) = pivot + R(t) (x_placed - pivot) + translate(t).
// A script gives the motion as a Lua function of t (scripting/lua_motion.cpp) or as a table
// of keyframes, interpolated here.
#include <array>
#include <string>
#include <vector>

#include "engine/geometry/shape.hpp"

namespace pbf {

struct Pose {
  std::array<double, 3> translate{0, 0, 0};
  std::array<double, 3> rotate_deg{0, 0, 0};
  bool operator==(const Pose&) const = default;
};

class Motion {
 public:
  virtual ~Motion() = default;
  // The pose at time t; throws Error when it cannot be had (a script error, a NaN).
  virtual Pose at(double t) const = 0;
  // One line for logs, restarts and `format_value`.
  virtual std::string description() const = 0;
};

// Throws unless the pose a script's function returned has finite numbers of magnitude at
// most 1e6 (`what` names the function and the time).
void check_pose(const Pose& pose, const std::string& what);

// Poses at given times, linear between them or on a Catmull-Rom spline through them (C1:
// no jump in the wall's velocity at a key). Before the first key the solid holds the first
// pose, after the last the last.
class Keyframes : public Motion {
 public:
  enum class Interpolation { linear, spline };
  struct Key {
    double t = 0;
    Pose pose;
  };
  // Refuses keys that are not in increasing time order, or not finite (`what` names them).
  Keyframes(std::vector<Key> keys, Interpolation interpolation, const std::string& what);
  Pose at(double t) const override;
  std::string description() const override;

 private:
  std::vector<Key> keys_;
  Interpolation interpolation_;
};

// x -> R x + c, the placed solid carried to its pose.
struct RigidTransform {
  std::array<double, 9> R{1, 0, 0, 0, 1, 0, 0, 0, 1};  // row major
  std::array<double, 3> c{0, 0, 0};

  Point apply(const Point& x) const;
  Point apply_inverse(const Point& x) const;  // R^T (x - c)
  Point rotate(const Point& v) const;         // R v
  Point rotate_inverse(const Point& v) const;  // R^T v
  bool identity() const;
  bool operator==(const RigidTransform&) const = default;
};

RigidTransform transform_of(const Pose& pose, const Point& pivot);

}  // namespace pbf
