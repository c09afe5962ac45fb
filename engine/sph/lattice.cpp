#include "engine/sph/lattice.hpp"

#include <cmath>
#include <fmt/format.h>

#include "engine/core/error.hpp"
#include "engine/sph/mass.hpp"
#include "engine/core/simulation.hpp"

namespace pbf {

std::size_t add_lattice(Simulation& sim, const double lo[3], const double hi[3], double spacing,
                        const double velocity[3], const double* sphere_center, double sphere_radius) {
  if (!(spacing > 0) || !std::isfinite(spacing))
    throw Error(fmt::format("lattice: spacing must be positive, got {}", spacing));
  if (sim.kernel_radius() <= 0) throw Error("lattice: set the kernel radius (pbf.kernel_radius) first");
  long count[3];
  for (int a = 0; a < 3; ++a) {
    if (!(hi[a] > lo[a])) throw Error(fmt::format("lattice: hi must exceed lo along {}", "xyz"[a]));
    if (lo[a] < sim.domain().lo[a] || hi[a] > sim.domain().hi[a])
      throw Error(fmt::format("lattice: region [{}, {}] along {} is not inside the domain [{}, {}]", lo[a], hi[a],
                              "xyz"[a], sim.domain().lo[a], sim.domain().hi[a]));
    count[a] = static_cast<long>(std::floor((hi[a] - lo[a]) / spacing + 1e-9));
  }
  const double total = static_cast<double>(count[0]) * static_cast<double>(count[1]) * static_cast<double>(count[2]);
  if (total > 2e9) throw Error(fmt::format("lattice: {:.3g} particles is too many", total));
  const real mass = real(lattice_mass(spacing, sim.kernels(), sim.rest_density()));
  const real v[3] = {real(velocity[0]), real(velocity[1]), real(velocity[2])};
  std::size_t added = 0;
  for (long k = 0; k < count[2]; ++k)
    for (long j = 0; j < count[1]; ++j)
      for (long i = 0; i < count[0]; ++i) {
        const double q[3] = {lo[0] + (i + 0.5) * spacing, lo[1] + (j + 0.5) * spacing, lo[2] + (k + 0.5) * spacing};
        if (sphere_radius > 0) {
          const double dx = q[0] - sphere_center[0], dy = q[1] - sphere_center[1], dz = q[2] - sphere_center[2];
          if (dx * dx + dy * dy + dz * dz > sphere_radius * sphere_radius) continue;
        }
        const real p[3] = {real(q[0]), real(q[1]), real(q[2])};
        sim.particles().add(p, v, mass);
        ++added;
      }
  sim.positions_changed();
  return added;
}

}  // namespace pbf
