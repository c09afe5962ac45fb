#include "engine/sph/wall_density.hpp"

#include <cmath>

#include "engine/core/simulation.hpp"
#include "engine/sph/mass.hpp"

namespace pbf {

bool HalfSpaceWall::prepare(const Simulation& sim) {
  const double mass = sim.particle_mass();
  if (mass == 0) return false;  // no particles yet: nothing to prepare for
  if (mass == prepared_[0] && sim.kernel_radius() == prepared_[1] && sim.rest_density() == prepared_[2]) return false;
  prepared_[0] = mass;
  prepared_[1] = sim.kernel_radius();
  prepared_[2] = sim.rest_density();
  h_ = sim.kernels().h;
  inv_h_ = 1 / h_;
  const double spacing = lattice_spacing(mass, sim.kernels(), sim.rest_density());
  const double missing = lattice_wall_density(mass, sim.kernels(), sim.rest_density()) / sim.rest_density();
  // f falls with the distance: bisect for the delta at which the first layer misses `missing`.
  double lo = -0.5 * spacing, hi = sim.kernel_radius();
  delta_ = 0;
  for (int it = 0; it < 100; ++it) {
    const double mid = 0.5 * (lo + hi);
    real slope;
    (fraction(real(0.5 * spacing + mid), slope) > missing ? lo : hi) = mid;  // with delta_ = 0
  }
  delta_ = real(0.5 * (lo + hi));
  return true;
}

}  // namespace pbf
