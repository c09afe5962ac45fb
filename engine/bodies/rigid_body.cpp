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
  double e = 0.5 * mass_ * (velocity_[0] * velocity_[0] + velocity_[1] * velocity_[1] + velocity_[2] * velocity_[2]);
  if (freedom_.turn == Freedom::Turn::about_axis) {
    // A hinge's centre moves with the turn: its energy is all in I_e (the pivot's moment).
    return (freedom_.hinged ? 0 : e) + 0.5 * axis_moment_ * spin_ * spin_;
  }
  const Vec L = orientation_.conjugate().rotate(angular_momentum_);
  for (int k = 0; k < 3; ++k) e += 0.5 * L[k] * L[k] / moments_[k];
  return e;
}

void RigidBody::restrict(const Freedom& freedom) {
  const Vec w = angular_velocity();
  freedom_ = freedom;
  if (freedom_.turn == Freedom::Turn::about_axis) {
    const Vec e = unit(freedom_.axis), b = orientation_.conjugate().rotate(e);
    axis_moment_ = moments_[0] * b[0] * b[0] + moments_[1] * b[1] * b[1] + moments_[2] * b[2] * b[2];
    if (freedom_.hinged) {
      const Vec r{position_[0] - freedom_.pivot[0], position_[1] - freedom_.pivot[1], position_[2] - freedom_.pivot[2]};
      const Vec d = cross(r, e);
      axis_moment_ += mass_ * (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      freedom_.move = {false, false, false};
    }
  }
  set_velocity(velocity_);
  set_angular_velocity(w);
}

void RigidBody::set_velocity(const Vec& v) {
  for (int a = 0; a < 3; ++a) velocity_[a] = freedom_.move[a] ? v[a] : 0;
  if (freedom_.hinged) {  // the centre goes round the pivot: w x (x - p)
    const Vec r{position_[0] - freedom_.pivot[0], position_[1] - freedom_.pivot[1], position_[2] - freedom_.pivot[2]};
    velocity_ = cross(angular_velocity(), r);
  }
}

void RigidBody::set_angular_velocity(const Vec& omega) {
  switch (freedom_.turn) {
    case Freedom::Turn::none:
      angular_momentum_ = {0, 0, 0};
      return;
    case Freedom::Turn::about_axis:
      spin_ = omega[static_cast<std::size_t>(freedom_.axis)];
      angular_momentum_ = {0, 0, 0};
      if (freedom_.hinged) set_velocity(velocity_);
      return;
    case Freedom::Turn::free: break;
  }
  const Vec w = orientation_.conjugate().rotate(omega);
  angular_momentum_ = orientation_.rotate({moments_[0] * w[0], moments_[1] * w[1], moments_[2] * w[2]});
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
  switch (freedom_.turn) {
    case Freedom::Turn::free:
      for (int a = 0; a < 3; ++a) angular_momentum_[a] += torque[a] * dt;
      break;
    case Freedom::Turn::about_axis: {
      const auto k = static_cast<std::size_t>(freedom_.axis);
      double t = torque[k];
      if (freedom_.hinged) {  // the force's moment about the pivot
        const Vec r{position_[0] - freedom_.pivot[0], position_[1] - freedom_.pivot[1], position_[2] - freedom_.pivot[2]};
        t += cross(r, force)[k];
      }
      spin_ += t / axis_moment_ * dt;
      break;
    }
    case Freedom::Turn::none: break;
  }
  if (freedom_.hinged) {
    set_velocity(velocity_);
  } else {
    for (int a = 0; a < 3; ++a)
      if (freedom_.move[a]) velocity_[a] += force[a] / mass_ * dt;
  }
  count_held(before, {force[0] * dt, force[1] * dt, force[2] * dt});
}

void RigidBody::apply_impulse(const Vec& J, const Vec& p) {
  const Vec before = velocity_;
  const Vec r{p[0] - position_[0], p[1] - position_[1], p[2] - position_[2]}, moment = cross(r, J);
  switch (freedom_.turn) {
    case Freedom::Turn::free:
      for (int a = 0; a < 3; ++a) angular_momentum_[a] += moment[a];
      break;
    case Freedom::Turn::about_axis: {
      const auto k = static_cast<std::size_t>(freedom_.axis);
      double m = moment[k];
      if (freedom_.hinged) {  // about the pivot: the centre's share too
        const Vec c{position_[0] - freedom_.pivot[0], position_[1] - freedom_.pivot[1], position_[2] - freedom_.pivot[2]};
        m += cross(c, J)[k];
      }
      spin_ += m / axis_moment_;
      break;
    }
    case Freedom::Turn::none: break;
  }
  if (freedom_.hinged) {
    set_velocity(velocity_);
  } else {
    for (int a = 0; a < 3; ++a)
      if (freedom_.move[a]) velocity_[a] += J[a] / mass_;
  }
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
    if (freedom_.hinged) {  // the centre turns round the pivot with the body
      const Vec r = turn.rotate({position_[0] - freedom_.pivot[0], position_[1] - freedom_.pivot[1],
                                 position_[2] - freedom_.pivot[2]});
      for (int a = 0; a < 3; ++a) position_[a] = freedom_.pivot[a] + r[a];
      const Vec before = velocity_;
      set_velocity(velocity_);  // turned with the body: the hinge's centripetal pull
      count_held(before, {0, 0, 0});
      return;
    }
  }
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
}

}  // namespace pbf
