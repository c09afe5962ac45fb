#include "engine/sph/mass.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "engine/core/parallel.hpp"
#include "engine/core/simulation.hpp"
#include "engine/distributed/comm.hpp"
#include "engine/distributed/selection.hpp"
#include "engine/sph/neighbor_grid.hpp"

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

double lattice_wall_shear(double mass, const Kernels& kernels, double rest_density) {
  const double spacing = lattice_spacing(mass, kernels, rest_density);
  const double eta2 = 0.01 * double(kernels.h2);
  double sum = 0;
  for_lattice_offsets(spacing, kernels.h, [&](double dx, double dy, double dz) {
    const double r2 = dx * dx + dy * dy + dz * dz;
    if (dz < -0.5 * spacing) sum -= double(kernels.grad_factor(real(r2))) * r2 / (r2 + eta2) * -dz;
  });
  return mass / rest_density * sum;
}

double lattice_laplacian(double mass, const Kernels& kernels, double rest_density) {
  const double spacing = lattice_spacing(mass, kernels, rest_density);
  const double eta2 = 0.01 * double(kernels.h2);
  double sum = 0;
  for_lattice_offsets(spacing, kernels.h, [&](double dx, double dy, double dz) {
    const double r2 = dx * dx + dy * dy + dz * dz;
    sum -= double(kernels.grad_factor(real(r2))) * r2 * dz * dz / (r2 + eta2);
  });
  return mass / rest_density * sum;
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

MassEstimate file_mass(Simulation& sim, std::int64_t first_id, std::int64_t end_id) {
  const double h = sim.kernel_radius(), rest_density = sim.rest_density();
  const auto n_file = static_cast<std::size_t>(end_id - first_id);
  if (n_file < 2) return {rest_density * std::pow(0.5 * h, 3), 0, 0.5 * h};
  sim.refresh_neighbors();  // (in a distributed run: places the particles first; collective)
  const Particles& P = sim.particles();
  const bool ranks = P.distributed();
  const NeighborGrid& grid = sim.neighbors();
  const Kernels& kernels = sim.kernels();
  const Domain& domain = sim.domain();
  const std::size_t n = P.size();
  const real *x = P.x(), *y = P.y(), *z = P.z();
  const std::int64_t* id = P.ids();
  auto of_file = [&](std::size_t i) { return id[i] >= first_id && id[i] < end_id; };
  auto away_from_faces = [&](std::size_t i) {
    const double p[3] = {x[i], y[i], z[i]};
    for (int a = 0; a < 3; ++a)
      if (!domain.periodic[a] && (p[a] - domain.lo[a] < h || domain.hi[a] - p[a] < h)) return false;
    return true;
  };
  // Each of the file's particles: its neighbours from the file, and the nearest one's distance
  // (h where it has none within h).
  std::vector<std::uint32_t> count(n, 0);
  std::vector<real> nearest;
  std::vector<real> nearest_of(n, real(h));
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    if (!of_file(i)) continue;
    double best = h * h;
    grid.for_each_neighbor(i, x, y, z, [&](std::uint32_t j, real dx, real dy, real dz, real) {
      if (!of_file(j)) return;
      ++count[i];
      best = std::min(best, double(dx) * dx + double(dy) * dy + double(dz) * dz);  // in double, as h * h
    });
    nearest_of[i] = real(std::sqrt(best));
  }
  for (std::size_t i = 0; i < n; ++i)
    if (of_file(i)) nearest.push_back(nearest_of[i]);
  // A full neighbourhood: away from the domain's faces and not at the fluid's own surface,
  // that is with (nearly) as many neighbours as the best-surrounded particle.
  double most = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (of_file(i) && away_from_faces(i)) most = std::max(most, double(count[i]));
  if (ranks) most = comm::max(most);
  auto interior = [&](std::size_t i) { return of_file(i) && away_from_faces(i) && count[i] >= 0.95 * most; };
  auto kernel_sum = [&](std::size_t i) {
    double s = kernels.W(0);
    grid.for_each_neighbor(i, x, y, z, [&](std::uint32_t j, real, real, real, real r2) {
      if (of_file(j)) s += kernels.W(r2);
    });
    return s;
  };
  const double interiors = deterministic_sum(n, [&](std::size_t i) { return interior(i) ? 1.0 : 0.0; }, ranks);
  // The median nearest-neighbour distance, over every rank's.
  const double spacing = nth_smallest(nearest, n_file / 2, ranks);
  if (interiors > 0) {
    const double sum = deterministic_sum(n, [&](std::size_t i) { return interior(i) ? kernel_sum(i) : 0.0; }, ranks);
    return {rest_density * interiors / sum, static_cast<std::size_t>(interiors), spacing};
  }
  return {rest_density * spacing * spacing * spacing, 0, spacing};
}


double lattice_gradient_norm(double mass, const Kernels& K, double rho0) {
  const double s = lattice_spacing(mass, K, rho0), h = K.h;
  const int reach = static_cast<int>(std::ceil(h / s));
  double sum = 0;
  for (int k = -reach; k <= reach; ++k)
    for (int j = -reach; j <= reach; ++j)
      for (int i = -reach; i <= reach; ++i) {
        const double r2 = (i * i + j * j + k * k) * s * s;
        if (r2 < h * h) sum += K.grad_factor(real(r2)) * r2;
      }
  return -mass / rho0 * sum / 3;
}

}  // namespace pbf
