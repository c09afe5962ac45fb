#include "engine/sph/mass.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "engine/sph/neighbor_grid.hpp"
#include "engine/core/parallel.hpp"

namespace pbf {

namespace {

// Calls visit(dx, dy, dz) for every lattice offset (including 0) closer than h.
template <class Visit>
void for_lattice_offsets(double spacing, double h, Visit&& visit) {
  const int reach = static_cast<int>(std::ceil(h / spacing));
  for (int k = -reach; k <= reach; ++k)
    for (int j = -reach; j <= reach; ++j)
      for (int i = -reach; i <= reach; ++i) {
        const double dx = i * spacing, dy = j * spacing, dz = k * spacing;
        if (dx * dx + dy * dy + dz * dz < h * h) visit(dx, dy, dz);
      }
}

}  // namespace

double lattice_mass(double spacing, const Kernels& kernels, double rest_density) {
  double sum = 0;
  for_lattice_offsets(spacing, kernels.h, [&](double dx, double dy, double dz) {
    sum += kernels.W(real(dx * dx + dy * dy + dz * dz));
  });
  return rest_density / sum;
}

double lattice_spacing(double mass, const Kernels& kernels, double rest_density) {
  // Bisection: the lattice mass grows with the spacing over this bracket.
  double lo = 0.05 * kernels.h, hi = 1.0 * kernels.h;
  for (int it = 0; it < 100; ++it) {
    const double mid = 0.5 * (lo + hi);
    (lattice_mass(mid, kernels, rest_density) < mass ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double lattice_wall_density(double mass, const Kernels& kernels, double rest_density) {
  const double spacing = lattice_spacing(mass, kernels, rest_density);
  double sum = 0;
  for_lattice_offsets(spacing, kernels.h, [&](double dx, double dy, double dz) {
    if (dz < -0.5 * spacing) sum += mass * kernels.W(real(dx * dx + dy * dy + dz * dz));
  });
  return sum;
}

double lattice_gradient_sum(double mass, const Kernels& kernels, double rest_density) {
  const double spacing = lattice_spacing(mass, kernels, rest_density);
  double gi[3] = {0, 0, 0}, sum_j = 0;
  for_lattice_offsets(spacing, kernels.h, [&](double dx, double dy, double dz) {
    const double r2 = dx * dx + dy * dy + dz * dz;
    const double g = mass / rest_density * kernels.grad_factor(real(r2));
    gi[0] += g * dx;
    gi[1] += g * dy;
    gi[2] += g * dz;
    sum_j += g * g * r2;
  });
  return gi[0] * gi[0] + gi[1] * gi[1] + gi[2] * gi[2] + sum_j;
}

MassEstimate mass_from_positions(const real* x, const real* y, const real* z, std::size_t n, const Domain& domain,
                                 const Kernels& kernels, double rest_density) {
  const double h = kernels.h;
  if (n < 2) return {rest_density * std::pow(0.5 * h, 3), 0, 0.5 * h};
  NeighborGrid grid;
  grid.bin(x, y, z, n, domain, h);
  grid.build_lists(x, y, z, h);
  auto away_from_faces = [&](std::size_t i) {
    const double p[3] = {x[i], y[i], z[i]};
    for (int a = 0; a < 3; ++a)
      if (p[a] - domain.lo[a] < h || domain.hi[a] - p[a] < h) return false;
    return true;
  };
  // A full neighbourhood: away from the domain's faces and not at the fluid's own surface,
  // that is with (nearly) as many neighbours as the best-surrounded particle.
  std::uint32_t most = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (away_from_faces(i)) most = std::max(most, grid.count(i));
  auto interior = [&](std::size_t i) { return away_from_faces(i) && grid.count(i) >= 0.95 * most; };
  auto kernel_sum = [&](std::size_t i) {
    double s = kernels.W(0);
    grid.for_each_neighbor(i, x, y, z, [&](std::uint32_t, real, real, real, real r2) { s += kernels.W(r2); });
    return s;
  };
  const double count = deterministic_sum(n, [&](std::size_t i) { return interior(i) ? 1.0 : 0.0; });
  // Median nearest-neighbour distance (h where a particle has no neighbour within h).
  std::vector<double> nearest(n);
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    double best = h * h;
    grid.for_each_neighbor(i, x, y, z, [&](std::uint32_t, real dx, real dy, real dz, real) {
      best = std::min(best, double(dx) * dx + double(dy) * dy + double(dz) * dz);  // in double, as h * h
    });
    nearest[i] = std::sqrt(best);
  }
  std::nth_element(nearest.begin(), nearest.begin() + static_cast<std::ptrdiff_t>(n / 2), nearest.end());
  const double spacing = nearest[n / 2];
  if (count > 0) {
    const double sum = deterministic_sum(n, [&](std::size_t i) { return interior(i) ? kernel_sum(i) : 0.0; });
    return {rest_density * count / sum, static_cast<std::size_t>(count), spacing};
  }
  return {rest_density * spacing * spacing * spacing, 0, spacing};
}

}  // namespace pbf
