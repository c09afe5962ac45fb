#pragma once
// What the outputs need to know of a solid: its name, its surface where it is now (world
// coordinates) and which side of it the fluid is on. The `solid` fix implements it.
#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "engine/geometry/triangle_mesh.hpp"

namespace pbf {

class SolidDynamics;

class SolidBody {
 public:
  virtual ~SolidBody() = default;
  // The solid's fix id, used in file names.
  virtual const std::string& name() const = 0;
  // The surface at the current time, in world coordinates.
  virtual const TriangleMesh& surface() const = 0;
  // Changes whenever the surface moves (a static solid keeps 0), so an output writes a
  // surface file again only when it changed.
  virtual std::uint64_t surface_version() const { return 0; }
  // The fastest any point of the surface moves between t and t + dt (m/s; 0 at rest), for
  // time-step control.
  virtual double max_speed(double /*t*/, double /*dt*/) const { return 0; }
  // True for a container (fluid inside the surface), false for an obstacle.
  virtual bool fluid_inside() const = 0;
  // What the fluid exerted on the solid, averaged over the last step: the force (N) and the
  // torque about the origin (N m), {fx, fy, fz, tx, ty, tz}.
  virtual std::array<double, 6> load() const { return {}; }
  // A body the fluid moves: its state now (nullptr for a solid at rest or moved by a script).
  virtual const SolidDynamics* dynamics() const { return nullptr; }
  // How deep a point lies behind the surface, inside the wall (m; negative on the fluid side,
  // infinite deep in the wall), where the solid stands now; nothing where that holds for no
  // whole run: before the run that builds the solid's map, or for a solid that moves.
  virtual std::optional<double> depth_in_wall(const std::array<double, 3>& /*point*/) const { return std::nullopt; }
  // Near the surface, where depth_in_wall answers: the distance from a point to the surface
  // (m, positive on the fluid side) and the unit normal into the fluid there; false elsewhere
  // (far in the fluid, deep in the wall, a solid that moves).
  virtual bool face_near(const std::array<double, 3>& /*point*/, double& /*distance*/,
                         std::array<double, 3>& /*normal*/) const {
    return false;
  }
};

}  // namespace pbf
