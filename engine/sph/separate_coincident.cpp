#include "engine/sph/separate_coincident.hpp"

#include <cmath>
#include <cstdint>
#include <vector>

#include <spdlog/spdlog.h>

#include "engine/core/simulation.hpp"
#include "engine/distributed/comm.hpp"

namespace pbf {

namespace {

// The 12 vertices of an icosahedron, (0, +-1, +-phi) and its cyclic permutations, each
// followed by its opposite; normalised where used. Distinct ones are 1.05 apart on the unit
// sphere, so the particles of one group land at least kApart h from one another.
constexpr double kPhi = 1.6180339887498949;
constexpr double kDirections[12][3] = {{0, 1, kPhi},  {0, -1, -kPhi}, {1, kPhi, 0},  {-1, -kPhi, 0},
                                       {kPhi, 0, 1},  {-kPhi, 0, -1}, {0, -1, kPhi}, {0, 1, -kPhi},
                                       {-1, kPhi, 0}, {1, -kPhi, 0},  {kPhi, 0, -1}, {-kPhi, 0, 1}};

}  // namespace

std::size_t separate_coincident(Simulation& sim) {
  auto& P = sim.particles();
  const std::size_t n = P.size();
  sim.refresh_neighbors();
  const auto& grid = sim.neighbors();
  const double h = sim.kernel_radius();
  const real close2 = real(kCoincident * h * kCoincident * h);
  real *x = P.x(), *y = P.y(), *z = P.z();
  const std::int64_t* id = P.ids();

  // Ranks first, from the start positions (gather form: each particle writes its own).
  std::vector<std::uint32_t> rank(n, 0);
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i)
    grid.for_each_neighbor(i, x, y, z, [&](std::uint32_t j, real, real, real, real r2) {
      if (r2 < close2 && id[j] < id[i]) ++rank[i];
    });

  const Domain& domain = sim.domain();
  const double norm = std::sqrt(1 + kPhi * kPhi);
  real* position[3] = {x, y, z};
  std::size_t moved = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (rank[i] == 0) continue;
    const std::uint32_t k = (rank[i] - 1) % 12, ring = (rank[i] - 1) / 12;
    const double distance = kApart * h * (1 + ring);
    for (int a = 0; a < 3; ++a) {
      const double from = position[a][i], step = distance * kDirections[k][a] / norm;
      const double lo = domain.lo[a], hi = domain.hi[a];
      // The other way where this way leaves the domain; not at all where neither fits.
      const double to = from + step >= lo && from + step <= hi ? from + step
                        : from - step >= lo && from - step <= hi ? from - step
                                                                 : from;
      position[a][i] = real(to);
    }
    ++moved;
  }
  if (P.distributed()) moved = static_cast<std::size_t>(comm::sum(static_cast<std::int64_t>(moved)));
  if (moved == 0) return 0;
  sim.positions_changed();
  spdlog::warn("{} particle{} started on top of another (closer than {:.3g} m, {} h): moved apart by {:.3g} m ({} h), "
               "the lowest id of each group staying in place",
               moved, moved == 1 ? "" : "s", kCoincident * h, kCoincident, kApart * h, kApart);
  return moved;
}

}  // namespace pbf
