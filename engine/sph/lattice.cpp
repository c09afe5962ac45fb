#include "engine/sph/lattice.hpp"

#include <cmath>
#include <fmt/format.h>

#include "engine/core/error.hpp"
#include "engine/geometry/shape.hpp"
#include "engine/sph/mass.hpp"
#include "engine/sph/resolution.hpp"
#include "engine/core/simulation.hpp"

namespace pbf {

std::size_t add_lattice(Simulation& sim, const double lo[3], const double hi[3], double spacing,
                        const double velocity[3], const Shape* inside) {
  if (!(spacing > 0) || !std::isfinite(spacing))
    throw Error(fmt::format("lattice: spacing must be positive, got {}", spacing));
  if (sim.kernel_radius() <= 0) throw Error("lattice: set the kernel radius (pbf.kernel_radius) first");
  sim.check_scale();
  double count[3];
  for (int a = 0; a < 3; ++a) {
    if (!(hi[a] > lo[a])) throw Error(fmt::format("lattice: hi must exceed lo along {}", "xyz"[a]));
    if (lo[a] < sim.domain().lo[a] || hi[a] > sim.domain().hi[a])
      throw Error(fmt::format("lattice: region [{}, {}] along {} is not inside the domain [{}, {}]", lo[a], hi[a],
                              "xyz"[a], sim.domain().lo[a], sim.domain().hi[a]));
    count[a] = std::floor((hi[a] - lo[a]) / spacing + 1e-9);  // in double: a tiny spacing gives a huge count
  }
  const double total = count[0] * count[1] * count[2];
  if (!std::isfinite(total))
    throw Error(fmt::format("lattice: the spacing {} m is too small: the region holds more sites than can be counted",
                            spacing));
  if (total < 1)
    throw Error(fmt::format("lattice: the region holds no lattice site: the spacing {} is larger than the region "
                            "along {}",
                            spacing, "xyz"[count[0] < 1 ? 0 : count[1] < 1 ? 1 : 2]));
  check_memory_for(sim.particles(), total, fmt::format("lattice: spacing {} m", spacing));
  // Before the mass rule, which sums over every lattice site within h.
  check_kernel_radius(sim.kernel_radius(), spacing, "pbf.lattice");
  const real mass = real(lattice_mass(spacing, sim.kernels(), sim.rest_density()));
  const real v[3] = {real(velocity[0]), real(velocity[1]), real(velocity[2])};
  std::size_t added = 0;
  const long nx = static_cast<long>(count[0]), ny = static_cast<long>(count[1]), nz = static_cast<long>(count[2]);
  for (long k = 0; k < nz; ++k)
    for (long j = 0; j < ny; ++j)
      for (long i = 0; i < nx; ++i) {
        const double q[3] = {lo[0] + (i + 0.5) * spacing, lo[1] + (j + 0.5) * spacing, lo[2] + (k + 0.5) * spacing};
        if (inside && inside->signed_distance({q[0], q[1], q[2]}) > 0) continue;
        const real p[3] = {real(q[0]), real(q[1]), real(q[2])};
        sim.particles().add(p, v, mass);
        ++added;
      }
  if (added == 0) throw Error("lattice: the shape holds no lattice site (smaller than the spacing?)");
  sim.positions_changed();
  return added;
}

}  // namespace pbf
