#include "engine/bodies/rigid_body.hpp"

namespace pbf {

namespace {

using Vec = RigidBody::Vec;

Vec cross(const Vec& a, const Vec& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

Vec unit(int axis) {
  Vec e{0, 0, 0};
  e[static_cast<std::size_t>(axis)] = 1;
  return e;
}

}  // namespace

bool RigidBody::Freedom::moves_along(int a) const {
  if (pinned) return false;
  return sliding ? slide[static_cast<std::size_t>(a)] != 0 : move[static_cast<std::size_t>(a)];
}

RigidBody::Vec RigidBody::Freedom::project(const Vec& v) const {
  if (pinned) return {0, 0, 0};
  if (sliding) {
    const double along = v[0] * slide[0] + v[1] * slide[1] + v[2] * slide[2];
    return {along * slide[0], along * slide[1], along * slide[2]};
  }
  return {move[0] ? v[0] : 0, move[1] ? v[1] : 0, move[2] ? v[2] : 0};
}

RigidBody::RigidBody(const MassProperties& p) : mass_(p.mass), position_(p.center) {
  Matrix3 axes;
  principal_axes(p.inertia, moments_, axes);
  orientation_ = Quaternion::from_matrix(axes);
}

// I_c w in the world: the body-frame components scaled by the principal moments.
RigidBody::Vec RigidBody::angular_momentum() const {
  if (freedom_.turn == Freedom::Turn::free) return angular_momentum_;
  const Vec w = orientation_.conjugate().rotate(angular_velocity());
  return orientation_.rotate({moments_[0] * w[0], moments_[1] * w[1], moments_[2] * w[2]});
}

RigidBody::Vec RigidBody::angular_velocity() const {
  switch (freedom_.turn) {
    case Freedom::Turn::none: return {0, 0, 0};
    case Freedom::Turn::about_axis: {
      Vec w = unit(freedom_.axis);
      for (double& c : w) c *= spin_;
      return w;
    }
    case Freedom::Turn::free: break;
  }
  const Vec L = orientation_.conjugate().rotate(angular_momentum_);
  return orientation_.rotate({L[0] / moments_[0], L[1] / moments_[1], L[2] / moments_[2]});
}

double RigidBody::kinetic_energy() const {
  // A pinned body's centre moves with the turn: its energy is all in the pivot's moments.
  double e = freedom_.pinned ? 0
                             : 0.5 * mass_ *
                                   (velocity_[0] * velocity_[0] + velocity_[1] * velocity_[1] + velocity_[2] * velocity_[2]);
  if (freedom_.turn == Freedom::Turn::about_axis) return e + 0.5 * axis_moment_ * spin_ * spin_;
  const Vec L = orientation_.conjugate().rotate(angular_momentum_);
  for (int k = 0; k < 3; ++k) e += 0.5 * L[k] * L[k] / moments_[k];
  return e;
}

void RigidBody::restrict(const Freedom& freedom) {
  const Vec w = angular_velocity();
  freedom_ = freedom;
  const Vec r = from_pivot();
  if (freedom_.turn == Freedom::Turn::about_axis) {
    const Vec e = unit(freedom_.axis), b = orientation_.conjugate().rotate(e);
    axis_moment_ = moments_[0] * b[0] * b[0] + moments_[1] * b[1] * b[1] + moments_[2] * b[2] * b[2];
    if (freedom_.pinned) {
      const Vec d = cross(r, e);
      axis_moment_ += mass_ * (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    }
  } else if (freedom_.turn == Freedom::Turn::free && freedom_.pinned) {
    // I_p in the body's frame, and its principal axes: the body turns on those from now on.
    const Vec a = orientation_.conjugate().rotate(r);
    const double aa = a[0] * a[0] + a[1] * a[1] + a[2] * a[2];
    Matrix3 pivot_inertia{};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) pivot_inertia[i][j] = (i == j) * moments_[i] + mass_ * ((i == j) * aa - a[i] * a[j]);
    Matrix3 axes;
    principal_axes(pivot_inertia, moments_, axes);
    const Quaternion to_old = Quaternion::from_matrix(axes);
    orientation_ = (orientation_ * to_old).normalized();
    arm_ = to_old.conjugate().rotate(a);
  }
  set_velocity(velocity_);
  set_angular_velocity(w);
}

void RigidBody::set_velocity(const Vec& v) {
  velocity_ = freedom_.project(v);
  if (freedom_.pinned) velocity_ = cross(angular_velocity(), from_pivot());  // the centre goes round the pivot
}

void RigidBody::set_angular_velocity(const Vec& omega) {
  switch (freedom_.turn) {
    case Freedom::Turn::none:
      angular_momentum_ = {0, 0, 0};
      return;
    case Freedom::Turn::about_axis:
      spin_ = omega[static_cast<std::size_t>(freedom_.axis)];
      angular_momentum_ = {0, 0, 0};
      break;
    case Freedom::Turn::free: {
      const Vec w = orientation_.conjugate().rotate(omega);
      angular_momentum_ = orientation_.rotate({moments_[0] * w[0], moments_[1] * w[1], moments_[2] * w[2]});
      break;
    }
  }
  if (freedom_.pinned) set_velocity(velocity_);
}

RigidBody::Vec RigidBody::from_pivot() const {
  return {position_[0] - freedom_.pivot[0], position_[1] - freedom_.pivot[1], position_[2] - freedom_.pivot[2]};
}

void RigidBody::set_state(const Vec& position, const Vec& velocity, const Quaternion& orientation,
                          const Vec& angular_momentum, double spin) {
  position_ = position;
  velocity_ = velocity;
  orientation_ = orientation;
  angular_momentum_ = angular_momentum;
  spin_ = spin;
}

void RigidBody::count_held(const Vec& before, const Vec& applied) {
  for (int a = 0; a < 3; ++a) held_impulse_[a] += mass_ * (velocity_[a] - before[a]) - applied[a];
}

void RigidBody::kick(const Vec& force, const Vec& torque, double dt) {
  const Vec before = velocity_;
  turn_by({torque[0] * dt, torque[1] * dt, torque[2] * dt}, {force[0] * dt, force[1] * dt, force[2] * dt});
  count_held(before, {force[0] * dt, force[1] * dt, force[2] * dt});
}

// An angular impulse about the centre and an impulse J through it, as the freedom lets them.
void RigidBody::turn_by(const Vec& moment, const Vec& J) {
  Vec about = moment;
  if (freedom_.pinned) {  // about the pivot: the impulse's moment there too
    const Vec m = cross(from_pivot(), J);
    for (int a = 0; a < 3; ++a) about[a] += m[a];
  }
  switch (freedom_.turn) {
    case Freedom::Turn::free:
      for (int a = 0; a < 3; ++a) angular_momentum_[a] += about[a];
      break;
    case Freedom::Turn::about_axis: spin_ += about[static_cast<std::size_t>(freedom_.axis)] / axis_moment_; break;
    case Freedom::Turn::none: break;
  }
  const Vec dv = freedom_.project({J[0] / mass_, J[1] / mass_, J[2] / mass_});
  for (int a = 0; a < 3; ++a) velocity_[a] += dv[a];
  if (freedom_.pinned) set_velocity(velocity_);
}

void RigidBody::apply_impulse(const Vec& J, const Vec& p) {
  const Vec before = velocity_;
  turn_by(cross({p[0] - position_[0], p[1] - position_[1], p[2] - position_[2]}, J), J);
  count_held(before, J);
}

RigidBody::Vec RigidBody::velocity_at(const Vec& p) const {
  const Vec w = angular_velocity(), r{p[0] - position_[0], p[1] - position_[1], p[2] - position_[2]}, spin = cross(w, r);
  return {velocity_[0] + spin[0], velocity_[1] + spin[1], velocity_[2] + spin[2]};
}

double RigidBody::response(const Vec& p, const Vec& n) const {
  RigidBody pushed = *this;
  pushed.apply_impulse(n, p);
  const Vec before = velocity_at(p), after = pushed.velocity_at(p);
  return (after[0] - before[0]) * n[0] + (after[1] - before[1]) * n[1] + (after[2] - before[2]) * n[2];
}

void RigidBody::drift(double dt) {
  if (freedom_.turn == Freedom::Turn::about_axis) {
    const Vec e = unit(freedom_.axis);
    const Quaternion turn = Quaternion::about(e, spin_ * dt);
    orientation_ = (turn * orientation_).normalized();
    if (freedom_.pinned) {  // the centre turns round the pivot with the body
      const Vec r = turn.rotate(from_pivot());
      for (int a = 0; a < 3; ++a) position_[a] = freedom_.pivot[a] + r[a];
      carried_round();
      return;
    }
  }
  if (!freedom_.pinned)
    for (int a = 0; a < 3; ++a) position_[a] += velocity_[a] * dt;
  if (freedom_.turn != Freedom::Turn::free) return;
  // R_k(h): L seen from the body, L_k / I_k the rate about axis k; the body turns by it.
  auto turn = [&](int k, double h) {
    const Vec L = orientation_.conjugate().rotate(angular_momentum_);
    orientation_ = (orientation_ * Quaternion::about_axis(k, h * L[k] / moments_[k])).normalized();
  };
  turn(0, 0.5 * dt);
  turn(1, 0.5 * dt);
  turn(2, dt);
  turn(1, 0.5 * dt);
  turn(0, 0.5 * dt);
  if (freedom_.pinned) {  // a ball joint: the centre where the turn put it
    const Vec r = orientation_.rotate(arm_);
    for (int a = 0; a < 3; ++a) position_[a] = freedom_.pivot[a] + r[a];
    carried_round();
  }
}

// The velocity of a centre the pivot carried round: w x (x - p) where it is now, the change the
// pivot's pull (centripetal), counted as held.
void RigidBody::carried_round() {
  const Vec before = velocity_;
  set_velocity(velocity_);
  count_held(before, {0, 0, 0});
}

}  // namespace pbf
