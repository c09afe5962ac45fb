#pragma once
// What the tests of bodies share (test_floating.cpp, test_joints.cpp): a fix by style, a
// solid's body, and a small block of fluid in a corner for scenes that are about the bodies.
#include <memory>
#include <string>

#include "engine/bodies/rigid_body.hpp"
#include "engine/core/error.hpp"
#include "engine/core/simulation.hpp"
#include "engine/fixes/solid_dynamics.hpp"
#include "engine/geometry/solid_body.hpp"
#include "engine/registry/style_registry.hpp"
#include "engine/sph/lattice.hpp"

namespace pbf::test {

inline std::unique_ptr<Fix> fix(const std::string& id, const std::string& style, const GivenParams& p = {}) {
  return StyleRegistry::builtin().make_fix(id, style, p);
}

inline const SolidDynamics& dynamics_of(const Simulation& sim, const std::string& name) {
  for (const SolidBody* s : sim.solid_bodies())
    if (s->name() == name && s->dynamics()) return *s->dynamics();
  throw Error("no body " + name);
}

// The body of a solid fix alone (no run): its mass properties as the fix computes them.
inline RigidBody body_of(const GivenParams& p) {
  Simulation sim;
  sim.set_domain(Domain{{-1, -1, -1}, {1, 1, 1}});
  sim.add_fix(fix("b", "solid", p));
  return dynamics_of(sim, "b").body();
}

// A small block of fluid in a corner (a scene needs particles), spacing 1 cm, in a domain
// 0.4 x 0.2 x 0.4 m.
inline void corner_block(Simulation& sim) {
  sim.set_domain(Domain{{0, 0, 0}, {0.4, 0.2, 0.4}});
  sim.set_kernel_radius(0.02);
  sim.set_timestep(0.002);
  const double lo[3] = {0, 0, 0}, hi[3] = {0.04, 0.04, 0.04}, v[3] = {0, 0, 0};
  add_lattice(sim, lo, hi, 0.01, v);
}

// The corner block under gravity, with PBF and the box's walls: a scene about its bodies.
inline void corner_scene(Simulation& sim) {
  corner_block(sim);
  sim.add_fix(fix("gravity", "gravity"));
  sim.add_fix(fix("pbf", "pbf"));
  sim.add_fix(fix("walls", "box"));
}

}  // namespace pbf::test
