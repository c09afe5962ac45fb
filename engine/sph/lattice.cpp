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
  // In a distributed run each rank creates its share of the sites (in the same order).
  Particles& P = sim.particles();
  const auto sites = static_cast<std::size_t>(total);
  const Particles::Share share = P.share(sites);
  check_memory_for(P, static_cast<double>(share.end - share.first), fmt::format("lattice: spacing {} m", spacing));
  // Before the mass rule, which sums over every lattice site within h.
  check_kernel_radius(sim.kernel_radius(), spacing, "pbf.lattice");
  const real mass = real(lattice_mass(spacing, sim.kernels(), sim.rest_density()));
  const real v[3] = {real(velocity[0]), real(velocity[1]), real(velocity[2])};
  const std::size_t nx = static_cast<std::size_t>(count[0]), ny = static_cast<std::size_t>(count[1]);
  const std::size_t first = P.size();
  for (std::size_t site = share.first; site < share.end; ++site) {  // x fastest, then y, then z
    const std::size_t i = site % nx, j = site / nx % ny, k = site / nx / ny;
    const double q[3] = {lo[0] + (double(i) + 0.5) * spacing, lo[1] + (double(j) + 0.5) * spacing,
                         lo[2] + (double(k) + 0.5) * spacing};
    if (inside && inside->signed_distance({q[0], q[1], q[2]}) > 0) continue;
    const real p[3] = {real(q[0]), real(q[1]), real(q[2])};
    P.add(p, v, mass);
  }
  const std::size_t added = P.finish_source(first);
  if (added == 0) throw Error("lattice: the shape holds no lattice site (smaller than the spacing?)");
  sim.positions_changed();
  return added;
}

}  // namespace pbf
