#pragma once
// Something besides fluid particles that adds to a particle's density (walls). The
// density solver adds rho_b(x) to the SPH sum and its gradient to the constraint gradient.
#include <cstddef>

#include "engine/core/real.hpp"

namespace pbf {

class Simulation;

class DensityBoundary {
 public:
  virtual ~DensityBoundary() = default;
  // Brings constants that depend on the scene (h, rho0, particle mass) up to date; called
  // before a run and before the engine measures densities.
  virtual void prepare(const Simulation&) {}
  // Adds the boundary density at (x, y, z) to `rho` and its gradient to `grad`. `particle`:
  // the memory index of the particle at (x, y, z) during a step, which lets a boundary use
  // what it knows of that particle since the step began; kNoParticle for any other point.
  static constexpr std::size_t kNoParticle = ~std::size_t(0);
  virtual void add_density(const Simulation& sim, real x, real y, real z, std::size_t particle, real& rho,
                           real grad[3]) const = 0;
  // Adds the wall's moment at q (memory index `particle`, as for add_density),
  //   M = sum over the wall's fluid k of m_k gradW(q - x_k) (x) (x_k - q)
  // (symmetric: xx, yy, zz, xy, xz, yz, in `moment`), with which a pressure varying through
  // the wall's fluid pushes: a mirrored wall whose pressure rises with depth as the fluid's
  // does (engine/fixes/dfsph.cpp). rho0 times engine/sph/wall_density.hpp's moments for a flat
  // wall, A n n + B (1 - n n), with the part along the wall, B, weighed by `along` (the share
  // of the wall's fluid beside the particle that lies below the free surface). A wall that
  // does not say adds none (its pressure is the particle's own).
  virtual void add_moment(const Simulation& /*sim*/, const real /*q*/[3], std::size_t /*particle*/, real /*along*/,
                          real /*moment*/[6]) const {}
  // The wall's velocity at (x, y, z) over the current step, into `v`; false (and `v` left
  // alone) for a wall at rest. A density that is integrated in time (WCSPH's continuity
  // equation) sees the fluid approach the wall at its velocity relative to the wall.
  virtual bool wall_velocity(const Simulation& /*sim*/, const real /*q*/[3], real /*v*/[3]) const { return false; }
  // Whether the wall is no-slip for the Laplacian viscosity: it then adds its viscous pull
  // (engine/sph/viscous_wall.hpp). Free-slip walls add none.
  virtual bool no_slip() const { return false; }
  // A no-slip wall's pull on the particle at q (memory index `particle`, as for add_density)
  // moving at v: Psi(d) (v_wall - v)_t, added to `pull` (1/m^2 times m/s); the viscosity
  // multiplies it by nu (1 + rho0 / rho_i).
  virtual void add_no_slip(const Simulation& /*sim*/, const real /*q*/[3], std::size_t /*particle*/,
                           const real /*v*/[3], real /*pull*/[3]) const {}
  // The solver's term for this boundary gave particle i (memory index) the momentum
  // `momentum` (kg m/s) in this step: a boundary that reports the load on itself adds it up
  // (Newton's third law). Called from parallel loops, each index by one thread at a time.
  virtual void record_push(std::size_t /*i*/, const real /*momentum*/[3]) {}
};

}  // namespace pbf
