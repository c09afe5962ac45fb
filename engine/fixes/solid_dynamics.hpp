#pragma once
// A `solid` that the fluid moves (one with a `density` or a `mass`): its mass properties, how
// it is held (axes locked, a hinge), how long it is held before release, and its motion under
// gravity and the fluid's load, step by step. The equations are at the top of solid_dynamics.cpp.
#include <array>
#include <string>
#include <vector>

#include "engine/bodies/rigid_body.hpp"
#include "engine/fixes/solid_shape.hpp"
#include "engine/geometry/motion.hpp"
#include "engine/io/bytes.hpp"
#include "engine/registry/params.hpp"

namespace pbf {

class SolidDynamics;

// What pulls on bodies besides the fluid and gravity (a `spring`, engine/fixes/spring.cpp).
class BodyForce {
 public:
  virtual ~BodyForce() = default;
  // Adds the force (N) and its torque about the body's centre (N m) on `body`, at the state
  // the bodies are in now.
  virtual void add_to(const SolidDynamics& body, std::array<double, 3>& force, std::array<double, 3>& torque) const = 0;
};

class SolidDynamics {
 public:
  using Vec = RigidBody::Vec;

  // The `solid` parameters that make it a body.
  static std::vector<ParamSpec> params();
  static bool wanted(const Params& p) { return p.has("density") || p.has("mass"); }
  // Reads them (and checks them: one message naming the parameter); `shape` gives the mass
  // properties a density or a mass leaves unsaid.
  SolidDynamics(const std::string& id, const Params& p, const SolidShape& shape, bool fluid_inside);

  void set_gravity(const Vec& g) { gravity_ = g; }
  const RigidBody& body() const { return body_; }
  const Vec& placed_center() const { return placed_center_; }
  bool released(double t) const { return t >= hold_; }
  double contact_friction() const { return contact_friction_; }

  // The rigid map from where the scene placed the solid to where it is now.
  RigidTransform transform() const;
  // Where the step from t of dt will put it (for time-step control, ahead of the step).
  RigidTransform after_step(double t, double dt) const;
  // The step's first half: the kick of the last load and gravity over dt / 2 (begin_step),
  // contacts (solid_contact.cpp), the drift over dt (drift); start_step does both, contact-free.
  void begin_step(double t, double dt);
  void drift(double dt) {
    if (moved_) body_.drift(dt);
  }
  void start_step(double t, double dt) {
    begin_step(t, dt);
    drift(dt);
  }
  // Whether it moves in this step (released); a contact's impulse J at the world point p.
  bool moving() const { return moved_; }
  void push(const Vec& J, const Vec& p);
  // Over the last step (N): what the held axes and the hinge, and what contacts, exerted on it.
  Vec held_force() const;
  Vec contact_force() const;
  // Its second half: the kick of this step's load (force and torque about the origin, as the
  // solid measured it) and gravity over dt / 2. Throws when the body's state is no longer finite.
  void end_step(const std::array<double, 6>& load, double dt);
  // The pull of springs over the next half kick (force, torque about the centre), set for
  // every body before any is kicked, so that a spring between two pulls both alike.
  void set_pull(const std::array<double, 6>& pull) { pull_ = pull; }
  // The turn since the scene placed it, as a rotation vector (its axis times its angle, rad).
  Vec rotation() const;
  // The fluid's last load: force, and torque about the centre of mass.
  std::array<double, 6> fluid_load() const;

  void save(ByteWriter& w) const;
  void restore(ByteReader& r);

 private:
  static RigidBody::Freedom freedom_of(const Params& p);  // the held axes and joints the parameters give
  void kick(double dt);

  std::string id_;
  RigidBody body_;
  Vec placed_center_{};
  Quaternion placed_orientation_;
  Vec gravity_{0, 0, 0};
  double hold_ = 0, contact_friction_ = 0.5;
  Vec release_velocity_{}, release_angular_velocity_{};
  bool released_ = false, moved_ = false;  // released: set going; moved: in this step
  std::array<double, 6> load_{};           // the fluid's, about the origin
  std::array<double, 6> pull_{};           // the springs', about the centre
  Vec contact_impulse_{0, 0, 0}, held_{0, 0, 0};  // over the last step
  double dt_ = 0;                                   // the last step's
};

}  // namespace pbf
