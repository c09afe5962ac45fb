#include "engine/bodies/rigid_body.hpp"

namespace pbf {

RigidBody::RigidBody(const MassProperties& p) : mass_(p.mass), position_(p.center) {
  Matrix3 axes;
  principal_axes(p.inertia, moments_, axes);
  orientation_ = Quaternion::from_matrix(axes);
}

RigidBody::Vec RigidBody::angular_velocity() const {
  const Vec L = orientation_.conjugate().rotate(angular_momentum_);
  return orientation_.rotate({L[0] / moments_[0], L[1] / moments_[1], L[2] / moments_[2]});
}

double RigidBody::kinetic_energy() const {
  const Vec L = orientation_.conjugate().rotate(angular_momentum_);
  double e = 0.5 * mass_ * (velocity_[0] * velocity_[0] + velocity_[1] * velocity_[1] + velocity_[2] * velocity_[2]);
  for (int k = 0; k < 3; ++k) e += 0.5 * L[k] * L[k] / moments_[k];
  return e;
}

void RigidBody::set_angular_velocity(const Vec& omega) {
  const Vec w = orientation_.conjugate().rotate(omega);
  angular_momentum_ = orientation_.rotate({moments_[0] * w[0], moments_[1] * w[1], moments_[2] * w[2]});
}

void RigidBody::kick(const Vec& force, const Vec& torque, double dt) {
  for (int a = 0; a < 3; ++a) {
    velocity_[a] += force[a] / mass_ * dt;
    angular_momentum_[a] += torque[a] * dt;
  }
}

void RigidBody::drift(double dt) {
  for (int a = 0; a < 3; ++a) position_[a] += velocity_[a] * dt;
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
