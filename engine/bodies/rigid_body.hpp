#pragma once
// A rigid body's motion: its centre of mass x with velocity v, and its orientation q (body
// frame: the principal axes, moments I1 <= I2 <= I3) with angular momentum L in the world
// frame. Forces and torques about the centre come in as kicks; between them the body drifts:
//   kick:   v += F / m dt,   L += tau dt
//   drift:  x += v dt,       the free rotation over dt
// (a kick of dt/2, a drift of dt, a kick of dt/2: the velocity Verlet of the fluid's leapfrog).
//
// The free rotation is split into the rotations about each principal axis (Dullweber,
// Leimkuhler and McLachlan 1997, "Symplectic splitting methods for rigid body molecular
// dynamics"): the kinetic energy is H = sum_k L_k^2 / (2 I_k) in the body frame, and under one
// term alone the body turns about axis k at the rate L_k / I_k while L, seen from the body, turns
// back the other way, so that L in the world stays exactly where it was. The steps
//   R1(dt/2) R2(dt/2) R3(dt) R2(dt/2) R1(dt/2)
// compose a symmetric, symplectic step: L is kept to round-off, and the energy's error stays
// bounded (of order dt^2) over any number of turns instead of drifting.
//
// A body may be held (`Freedom`). Its centre translates along the free world axes, or along
// one direction u only (a slider: v = (v . u) u, the force projected so). Its rotation is free,
// none, or about one world axis e only. About one axis it turns at the rate w, with
//   I_e dw/dt = (tau + (x - p) x F) . e,   I_e = e . I_c e + m |(x - p) x e|^2
// (tau and I_c about the centre x) about a pivot p (a hinge: every translation locked, the
// centre carried round p), or about the centre itself (p = x: a body that heaves and rolls in
// 2D). I_e is constant: a body turning about e keeps e fixed in its own frame.
// Free about a pivot p (a ball joint), the body is a free rotor about p: its inertia there,
//   I_p = I_c + m (|r|^2 1 - r r^T),   r = x - p,
// is constant in its own frame, so the same splitting turns it on I_p's principal axes with the
// torque about p, tau + r x F, and the centre rides at p + r.
#include <array>

#include "engine/bodies/mass_properties.hpp"
#include "engine/bodies/quaternion.hpp"

namespace pbf {

class RigidBody {
 public:
  using Vec = std::array<double, 3>;

  struct Freedom {
    std::array<bool, 3> move{true, true, true};  // translation along x, y, z
    bool sliding = false;          // translation along `slide` (a unit vector) only, whatever `move` says
    Vec slide{1, 0, 0};
    enum class Turn { free, none, about_axis } turn = Turn::free;
    int axis = 0;                  // about_axis: the world axis 0, 1, 2
    bool pinned = false;           // turn about `pivot`, every translation locked: a hinge about
    Vec pivot{0, 0, 0};            // one axis, a ball joint when free
    // Whether the centre may move along world axis a; a vector with what it may not dropped.
    bool moves_along(int a) const;
    Vec project(const Vec& v) const;
  };

  RigidBody() = default;
  // A body of these mass properties, at rest where they place it.
  explicit RigidBody(const MassProperties& p);

  double mass() const { return mass_; }
  // I1 <= I2 <= I3 about the principal axes it turns on: the centre's (a ball joint's: the pivot's).
  const Vec& moments() const { return moments_; }
  const Vec& position() const { return position_; }
  const Vec& velocity() const { return velocity_; }
  const Quaternion& orientation() const { return orientation_; }  // principal frame to world
  Vec angular_momentum() const;  // world frame, about the centre (a ball joint's: the pivot)
  Vec angular_velocity() const;  // world frame
  double kinetic_energy() const;

  const Freedom& freedom() const { return freedom_; }
  // Holds the body so; its velocities lose what the freedom forbids. A pivot locks every
  // translation; about it, a free body turns on the pivot's principal axes from now on.
  void restrict(const Freedom& freedom);

  void set_velocity(const Vec& v);
  void set_angular_velocity(const Vec& omega);  // world frame
  // The state as it is (a restart's), set back exactly.
  void set_state(const Vec& position, const Vec& velocity, const Quaternion& orientation, const Vec& angular_momentum,
                 double spin);
  double spin() const { return spin_; }  // about_axis: the rate about the axis

  void kick(const Vec& force, const Vec& torque, double dt);
  // An impulse J at the world point p (contact): v += J / m, L += (p - x) x J, as the freedom
  // lets them; the velocity of the body's point at p; and the change of that velocity along
  // the unit n that a unit impulse along n at p makes (n . dv, 1 / effective mass).
  void apply_impulse(const Vec& J, const Vec& p);
  // The impulse the held axes and the hinge gave the centre since the last clear: m dv less
  // the impulses applied (their reaction, integrated).
  const Vec& held_impulse() const { return held_impulse_; }
  void clear_held_impulse() { held_impulse_ = {0, 0, 0}; }
  Vec velocity_at(const Vec& p) const;
  double response(const Vec& p, const Vec& n) const;
  void drift(double dt);

 private:
  double mass_ = 1;
  Vec moments_{1, 1, 1};
  Vec position_{0, 0, 0}, velocity_{0, 0, 0};
  Quaternion orientation_;
  Vec angular_momentum_{0, 0, 0};
  Freedom freedom_;
  double spin_ = 0, axis_moment_ = 0;  // about_axis: the rate w and the moment I_e
  Vec arm_{0, 0, 0};                   // a ball joint's: x - p in the body's frame
  Vec held_impulse_{0, 0, 0};
  // Adds m (v - before) - applied to held_impulse_.
  void count_held(const Vec& before, const Vec& applied);
  Vec from_pivot() const;  // x - p
  void turn_by(const Vec& moment, const Vec& J);
  void carried_round();
};

}  // namespace pbf
