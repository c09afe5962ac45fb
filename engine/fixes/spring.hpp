#pragma once
// spring: a linear spring with a damper from a point on a body to a fixed point, or to a point
// on another body (a mooring line, a tether, a suspension). With the points p (on `body`) and
// q (the anchor), d = q - p, L = |d|, u = d / L, its tension is
//   T = k (L - L0) + c (v_q - v_p) . u
// (k the stiffness, L0 the rest length, c the damping, v the points' velocities), and it
// pulls the body at p with T u and the other body at q with -T u. A `cable` pulls only: T < 0
// is 0 (a slack line). The bodies take the pull in their kicks (solid_dynamics.cpp), each
// half kick from the states before either moves, so a spring between two conserves momentum.
#include <array>
#include <string>

#include "engine/core/fix.hpp"
#include "engine/fixes/solid_dynamics.hpp"
#include "engine/registry/params.hpp"

namespace pbf {

class SpringFix : public Fix, public BodyForce {
 public:
  SpringFix(const std::string& id, const Params& p);

  std::vector<Stage> stages() const override { return {}; }
  bool runs_distributed() const override { return true; }  // every rank has the same bodies
  const BodyForce* body_force() const override { return this; }
  void init(Simulation& sim) override;
  void add_to(const SolidDynamics& body, std::array<double, 3>& force, std::array<double, 3>& torque) const override;

  // Now: the tension (N), the length (m) and the force on `body` (N).
  struct State {
    double tension = 0, length = 0;
    std::array<double, 3> force{0, 0, 0};
  };
  State state() const;

 private:
  using Vec = std::array<double, 3>;
  // The two ends and their velocities where the bodies are now.
  void ends(Vec& p, Vec& vp, Vec& q, Vec& vq) const;

  std::string body_name_, other_name_;
  Vec at_{}, to_{};  // as placed
  double stiffness_, rest_length_, damping_;
  bool cable_;
  const SolidDynamics* body_ = nullptr;
  const SolidDynamics* other_ = nullptr;  // nullptr: a fixed anchor
};

}  // namespace pbf
