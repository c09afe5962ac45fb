// A solid the fluid moves: a rigid body of mass m, centre x and inertia I_c (from the solid's
// closed surface at its density, or given), under gravity g and the fluid's load (F, tau), the
// load the solid measures as the opposite of the momentum its wall gave the fluid over the step
// (docs/physics.md, "Loads on solids"). A step from t to t + dt is the velocity Verlet of the
// fluid's leapfrog (engine/bodies/rigid_body.hpp: kicks, and the free rotation's splitting):
//   start of the step:  v += (F_n / m + g) dt / 2,  L += tau_n dt / 2;  drift over dt
//   the fluid's step, the wall where the drift put it: the load F_n+1, tau_n+1
//   end of the step:    v += (F_n+1 / m + g) dt / 2,  L += tau_n+1 dt / 2
// with tau about the centre where the drift put it: tau_c = tau_0 - x x F. Every rank sums the
// load over every rank's particles exactly (deterministic sums), so every rank steps the same
// body to the same bits. The fluid feels the body at the step it moves: the wall's velocity
// over the step is the drift's (solid.cpp), and the load it measures is its response.
//
// Held: axes locked (free_translation, free_rotation by world axis: 0, 1 or 3 rotations), a
// slider (the centre moves along one direction; no turn unless free_rotation says), a hinge
// (one rotation about a fixed point) or a ball joint (every rotation about a fixed point); a
// hinge and a ball joint lock every translation. Until `hold` the body
// stays where the scene put it (the fluid settles around it), then it starts with `velocity`
// and `angular_velocity`.
#include "engine/fixes/solid_dynamics.hpp"

#include <cmath>
#include <fmt/format.h>

#include "engine/core/error.hpp"

namespace pbf {

namespace {

using Vec = RigidBody::Vec;

Vec cross(const Vec& a, const Vec& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

// A vector of 0s and 1s: which world axes are free.
std::array<bool, 3> axes_of(const Params& p, const char* name) {
  const Vec3 v = p.has(name) ? p.vec3(name) : Vec3{1, 1, 1};
  std::array<bool, 3> free{};
  for (int a = 0; a < 3; ++a) {
    if (v[a] != 0 && v[a] != 1)
      throw Error(fmt::format("parameter '{}': each component is 1 (free) or 0 (locked), not {}", name, v[a]));
    free[a] = v[a] == 1;
  }
  return free;
}

// The rotation that takes the placed body's axes to its axes now, as a rigid map of the placed solid.
RigidTransform transform_between(const Vec& c0, const Quaternion& q0, const Vec& c, const Quaternion& q) {
  const auto M = (q * q0.conjugate()).matrix();
  RigidTransform T;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) T.R[3 * i + j] = M[i][j];
  const Point moved = T.rotate(c0);
  for (int a = 0; a < 3; ++a) T.c[a] = c[a] - moved[a];
  return T;
}

}  // namespace

std::vector<ParamSpec> SolidDynamics::params() {
  // (Without defaults in the schema: a solid that is no body is refused any of them.)
  return {
      ParamSpec{"density", ParamType::Real, std::nullopt, "kg/m^3",
                "makes the solid a body the fluid moves: its density (mass and inertia from its closed surface)", true}
          .above_within(0, 1e6),
      ParamSpec{"mass", ParamType::Real, std::nullopt, "kg",
                "makes the solid a body the fluid moves: its mass (inertia from its surface, or given)", true}
          .above_within(0, 1e12),
      ParamSpec{"center_of_mass", ParamType::Vector3, std::nullopt, "m",
                "a body's centre of mass where the scene places it (default: its volume's centroid)", true}
          .magnitude_at_most(1e6),
      ParamSpec{"inertia", ParamType::Vector3, std::nullopt, "kg m^2",
                "a body's moments of inertia about its centre of mass, along x, y, z as placed (default: from its "
                "surface)",
                true}
          .above_within(0, 1e12),
      ParamSpec{"inertia_products", ParamType::Vector3, std::nullopt, "kg m^2",
                "with inertia: the tensor's off-diagonal entries {Ixy, Ixz, Iyz} (default 0)", true}
          .magnitude_at_most(1e12),
      ParamSpec{"velocity", ParamType::Vector3, std::nullopt, "m/s", "a body's velocity at its release (default 0)",
                true}
          .magnitude_at_most(1e4),
      ParamSpec{"angular_velocity", ParamType::Vector3, std::nullopt, "rad/s",
                "a body's angular velocity at its release (default 0)", true}
          .magnitude_at_most(1e4),
      ParamSpec{"hold", ParamType::Real, std::nullopt, "s",
                "a body stays where placed until this time, then is released (default 0)", true}
          .within(0, 1e6),
      ParamSpec{"free_translation", ParamType::Vector3, std::nullopt, "",
                "a body's free translations along x, y, z, 1 or 0 (default {1, 1, 1})", true},
      ParamSpec{"free_rotation", ParamType::Vector3, std::nullopt, "",
                "a body's free rotations about x, y, z, 1 or 0: all three, one, or none (default {1, 1, 1})", true},
      ParamSpec{"contact_friction", ParamType::Real, std::nullopt, "",
                "a body's Coulomb friction coefficient in contact with walls and bodies (default 0.5; two "
                "bodies: the geometric mean)",
                true}
          .within(0, 10),
      ParamSpec{"hinge", ParamType::Vector3, std::nullopt, "m",
                "a point the body turns about, on its one free rotation's axis (every translation locked)", true}
          .magnitude_at_most(1e6),
      ParamSpec{"ball_joint", ParamType::Vector3, std::nullopt, "m",
                "a fixed point the body turns freely about (a ball joint; every translation locked)", true}
          .magnitude_at_most(1e6),
      ParamSpec{"slider", ParamType::Vector3, std::nullopt, "",
                "the one direction a body's centre moves along (a prismatic joint; it turns only as free_rotation "
                "says, default not at all)",
                true}
          .magnitude_at_most(1e6),
  };
}

SolidDynamics::SolidDynamics(const std::string& id, const Params& p, const SolidShape& shape, bool fluid_inside)
    : id_(id),
      hold_(p.has("hold") ? p.real("hold") : 0.0),
      contact_friction_(p.has("contact_friction") ? p.real("contact_friction") : 0.5) {
  if (p.has("density") && p.has("mass")) throw Error("give a body's 'density' or its 'mass', not both");
  if (p.has("motion")) throw Error("a body the fluid moves has no 'motion': drop 'motion' or 'density'/'mass'");
  if (p.has("inertia_products") && !p.has("inertia")) throw Error("'inertia_products' needs 'inertia'");
  const bool given_all = p.has("mass") && p.has("center_of_mass") && p.has("inertia");
  if (fluid_inside && !given_all)
    throw Error("a container (fluid inside) that the fluid moves needs 'mass', 'center_of_mass' and 'inertia': its "
                "surface does not enclose its walls' volume");
  MassProperties props;
  if (!given_all) {
    props = shape.mass_properties(p.has("density") ? p.real("density") : 1.0);
    if (p.has("mass")) {
      const double scale = p.real("mass") / props.mass;
      for (auto& row : props.inertia)
        for (double& v : row) v *= scale;
    }
  }
  if (p.has("mass")) props.mass = p.real("mass");
  if (p.has("center_of_mass")) {  // the surface's inertia about the given centre (parallel axes)
    const Vec3 c = p.vec3("center_of_mass");
    const Vec d{c[0] - props.center[0], c[1] - props.center[1], c[2] - props.center[2]};
    const double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) props.inertia[i][j] += props.mass * ((i == j) * dd - d[i] * d[j]);
    props.center = {c[0], c[1], c[2]};
  }
  if (p.has("inertia")) {
    const Vec3 diagonal = p.vec3("inertia"), off = p.has("inertia_products") ? p.vec3("inertia_products") : Vec3{};
    props.inertia = {{{diagonal[0], off[0], off[1]}, {off[0], diagonal[1], off[2]}, {off[1], off[2], diagonal[2]}}};
  }
  // A real body's inertia is positive definite, and each principal moment at most the sum of
  // the other two (equal for a flat plate).
  Vec moments;
  Matrix3 axes;
  principal_axes(props.inertia, moments, axes);
  if (!(moments[0] > 0))
    throw Error(fmt::format("parameter 'inertia': the inertia tensor is not positive definite (principal moments "
                            "{:.6g}, {:.6g}, {:.6g} kg m^2)",
                            moments[0], moments[1], moments[2]));
  if (moments[2] > (moments[0] + moments[1]) * (1 + 1e-9))
    throw Error(fmt::format("parameter 'inertia': no body has these principal moments ({:.6g}, {:.6g}, {:.6g} kg "
                            "m^2): the largest exceeds the sum of the other two",
                            moments[0], moments[1], moments[2]));
  body_ = RigidBody(props);

  body_.restrict(freedom_of(p));
  placed_center_ = body_.position();
  placed_orientation_ = body_.orientation();  // a ball joint turns the body's frame onto the pivot's axes
  const Vec3 zero{0, 0, 0}, v = p.has("velocity") ? p.vec3("velocity") : zero,
             w = p.has("angular_velocity") ? p.vec3("angular_velocity") : zero;
  release_velocity_ = {v[0], v[1], v[2]};
  release_angular_velocity_ = {w[0], w[1], w[2]};
}

RigidBody::Freedom SolidDynamics::freedom_of(const Params& p) {
  int joints = 0;
  for (const char* joint : {"hinge", "ball_joint", "slider"}) joints += p.has(joint);
  if (joints > 1) throw Error("give a body one of 'hinge', 'ball_joint' and 'slider'");
  if (p.has("free_translation") && joints > 0)
    throw Error("parameter 'free_translation': a body on a hinge, ball joint or slider moves as its joint lets it: drop "
                "'free_translation'");
  RigidBody::Freedom freedom;
  freedom.move = axes_of(p, "free_translation");
  if (p.has("slider")) {
    const Vec3 u = p.vec3("slider");
    const double length = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    if (!(length > 0)) throw Error("parameter 'slider': the direction has no length");
    freedom.sliding = true;
    freedom.slide = {u[0] / length, u[1] / length, u[2] / length};
  }
  const auto turn = p.has("free_rotation") || !p.has("slider") ? axes_of(p, "free_rotation")
                                                                : std::array<bool, 3>{false, false, false};
  const int turning = turn[0] + turn[1] + turn[2];
  if (turning == 2)
    throw Error("parameter 'free_rotation': free all three rotations, one, or none (two free rotations are no "
                "rigid body's motion about fixed axes)");
  freedom.turn = turning == 3   ? RigidBody::Freedom::Turn::free
                 : turning == 0 ? RigidBody::Freedom::Turn::none
                                : RigidBody::Freedom::Turn::about_axis;
  freedom.axis = turn[1] ? 1 : turn[2] ? 2 : 0;
  if (p.has("hinge")) {
    if (turning != 1)
      throw Error("parameter 'hinge': a hinge turns about one axis: free exactly one rotation (free_rotation, e.g. "
                  "{0, 1, 0})");
    const Vec3 h = p.vec3("hinge");
    freedom.pinned = true;
    freedom.pivot = {h[0], h[1], h[2]};
  }
  if (p.has("ball_joint")) {
    if (turning != 3)
      throw Error("parameter 'ball_joint': a body turns freely about its ball joint (for one axis, give 'hinge'): drop "
                  "'free_rotation'");
    const Vec3 c = p.vec3("ball_joint");
    freedom.pinned = true;
    freedom.pivot = {c[0], c[1], c[2]};
  }
  return freedom;
}

RigidTransform SolidDynamics::transform() const {
  return transform_between(placed_center_, placed_orientation_, body_.position(), body_.orientation());
}

RigidTransform SolidDynamics::after_step(double t, double dt) const {
  SolidDynamics ahead = *this;
  ahead.start_step(t, dt);
  return ahead.transform();
}

void SolidDynamics::kick(double dt) {
  const double m = body_.mass();
  const Vec F{load_[0] + m * gravity_[0] + pull_[0], load_[1] + m * gravity_[1] + pull_[1],
              load_[2] + m * gravity_[2] + pull_[2]};
  const auto fluid = fluid_load();
  body_.kick(F, {fluid[3] + pull_[3], fluid[4] + pull_[4], fluid[5] + pull_[5]}, dt);
}

void SolidDynamics::push(const Vec& J, const Vec& p) {
  body_.apply_impulse(J, p);
  for (int a = 0; a < 3; ++a) contact_impulse_[a] += J[a];
}

SolidDynamics::Vec SolidDynamics::held_force() const {
  // The held impulse counts the contacts' as applied: what is left is the constraints'.
  if (!(dt_ > 0)) return {0, 0, 0};
  return {held_[0] / dt_, held_[1] / dt_, held_[2] / dt_};
}

SolidDynamics::Vec SolidDynamics::contact_force() const {
  if (!(dt_ > 0)) return {0, 0, 0};
  return {contact_impulse_[0] / dt_, contact_impulse_[1] / dt_, contact_impulse_[2] / dt_};
}

void SolidDynamics::begin_step(double t, double dt) {
  contact_impulse_ = {0, 0, 0};
  dt_ = dt;
  moved_ = released(t);
  if (!moved_) return;
  if (!released_) {
    released_ = true;
    body_.set_velocity(release_velocity_);
    body_.set_angular_velocity(release_angular_velocity_);
  }
  kick(0.5 * dt);
}

void SolidDynamics::end_step(const std::array<double, 6>& load, double dt) {
  load_ = load;
  if (!moved_) return;
  kick(0.5 * dt);
  // The held impulse from the last reading to now (the step's last contacts count in the next).
  held_ = body_.held_impulse();
  body_.clear_held_impulse();
  const Vec x = body_.position(), v = body_.velocity(), w = body_.angular_velocity();
  if (!std::isfinite(x[0] + x[1] + x[2] + v[0] + v[1] + v[2] + w[0] + w[1] + w[2]))
    throw Error(fmt::format("body '{}' blew up: its position, velocity or angular velocity is no longer finite (the "
                            "fluid's load on it: {:.6g} {:.6g} {:.6g} N)",
                            id_, load[0], load[1], load[2]));
}

SolidDynamics::Vec SolidDynamics::rotation() const {
  Quaternion q = body_.orientation() * placed_orientation_.conjugate();
  if (q.w < 0) q = {-q.w, -q.x, -q.y, -q.z};  // the turn of at most half a revolution
  const double s = std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z);
  if (s == 0) return {0, 0, 0};
  const double angle = 2 * std::atan2(s, q.w);
  return {angle * q.x / s, angle * q.y / s, angle * q.z / s};
}

std::array<double, 6> SolidDynamics::fluid_load() const {
  const Vec c = body_.position(), F{load_[0], load_[1], load_[2]}, m = cross(c, F);
  return {load_[0], load_[1], load_[2], load_[3] - m[0], load_[4] - m[1], load_[5] - m[2]};
}

void SolidDynamics::save(ByteWriter& w) const {
  for (double v : body_.position()) w.put(v);
  for (double v : body_.velocity()) w.put(v);
  const Quaternion& q = body_.orientation();
  for (double v : {q.w, q.x, q.y, q.z}) w.put(v);
  for (double v : body_.angular_momentum()) w.put(v);
  w.put(body_.spin());
  for (double v : load_) w.put(v);
  w.put<std::uint8_t>(released_);
}

void SolidDynamics::restore(ByteReader& r) {
  Vec x, v, L;
  Quaternion q;
  for (double& c : x) c = r.get<double>();
  for (double& c : v) c = r.get<double>();
  for (double* c : {&q.w, &q.x, &q.y, &q.z}) *c = r.get<double>();
  for (double& c : L) c = r.get<double>();
  const double spin = r.get<double>();
  for (double& c : load_) c = r.get<double>();
  released_ = r.get<std::uint8_t>() != 0;
  body_.set_state(x, v, q, L, spin);
}

}  // namespace pbf
