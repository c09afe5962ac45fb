#include "engine/sph/wall_density.hpp"

#include <algorithm>
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

void HalfSpaceWall::moments(real d, real& normal, real& tangential) const {
  const double h = h_, z = std::clamp(double(d + delta_), 0.0, h);
  static constexpr double kNode[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
                                      0.9061798459386640};
  static constexpr double kWeight[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                                        0.4786286704993665, 0.2369268850561891};
  const double coef = 21.0 / (2.0 * M_PI * h * h * h), half = (h - z) / 2, mid = (h + z) / 2;
  double a = 0, b = 0;
  for (int k = 0; k < 5; ++k) {
    const double r = mid + half * kNode[k], q = r / h, slope = -20 * coef * q * (1 - q) * (1 - q) * (1 - q) / h;  // W'(r)
    a += kWeight[k] * slope * (r * r * r - z * z * z);
    b += kWeight[k] * slope * (2 * r * r * r / 3 - z * r * r + z * z * z / 3);
  }
  normal = real(-2 * M_PI / 3 * half * a);
  tangential = real(-M_PI * half * b);
}

}  // namespace pbf
