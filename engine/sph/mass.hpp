#pragma once
// The mass rule, shared by every solver: particle mass is chosen so that an interior
// particle (a full neighbourhood) has the rest density, as the original Fortran code
// rescaled it. One rule for lattices, one for particles read from a file.
#include <cstddef>
#include <cstdint>

#include "engine/core/domain.hpp"
#include "engine/sph/kernels.hpp"

namespace pbf {

class Simulation;

// rho0 / sum_j W(x_j) over an infinite cubic lattice of the given spacing.
double lattice_mass(double spacing, const Kernels& kernels, double rest_density);

struct MassEstimate {
  double mass;
  std::size_t interior;   // particles with a full neighbourhood used (0: fallback)
  double spacing;         // median nearest-neighbour distance (fallback rule)
};

// For particles read from a file, those with ids in [first_id, end_id) (already added, with
// any mass): rho0 / mean(sum_j W) over the particles with a full neighbourhood among the
// file's (at least h from every face of the domain, and at least 95% as many neighbours as the
// best-surrounded such particle, which leaves out the fluid's own free surface); without such
// particles, rho0 times the cube of the median nearest-neighbour spacing (h/2 for a single
// particle). Over the simulation's neighbour lists (by cell, then id), so the same on any
// rank count; collective in a distributed run.
MassEstimate file_mass(Simulation& sim, std::int64_t first_id, std::int64_t end_id);

// The lattice spacing at which `mass` gives an interior particle the rest density.
double lattice_spacing(double mass, const Kernels& kernels, double rest_density);

// The sum of squared constraint gradients, sum_k |grad_k C_i|^2, of a particle at rest
// inside an infinite cubic lattice whose spacing gives `mass` the rest density.
double lattice_gradient_sum(double mass, const Kernels& kernels, double rest_density);

// kappa = -1/3 sum_j V_j g(r_j) r_j^2 over that lattice, V_j = m / rho0 and gradW = g(r) r_vec:
// the SPH gradient of a linear field there, sum_j V_j (p_j - p_i) gradW_ij, is kappa times its
// gradient (0.950 at h = 2s). A solver's pressure that moves the fluid through this sum
// reports kappa p: the pressure whose exact gradient does the same (pbf, dfsph).
double lattice_gradient_norm(double mass, const Kernels& kernels, double rest_density);

// The density a particle of a lattice's first layer (at spacing/2 from a flat wall) misses:
// the sum over the lattice sites behind the wall.
double lattice_wall_density(double mass, const Kernels& kernels, double rest_density);

// What the lattice sites behind a flat wall give a particle of the first layer in the
// Laplacian viscosity's sum for a shear that is linear in the distance from the wall:
// sum_j V (-g(r_j)) r_j^2 / (r_j^2 + 0.01 h^2) s_j over those sites, V = mass / rho0, s_j their
// normal separation from the particle (1/m; engine/sph/viscous_wall.hpp).
double lattice_wall_shear(double mass, const Kernels& kernels, double rest_density);

// The Laplacian viscosity's lattice factor: what Morris's sum, sum_j 2 V (-g(r_j)) r_j^2 /
// (r_j^2 + 0.01 h^2) (u_j - u_i), gives a quadratic field u = z^2 / 2 (whose Laplacian is 1)
// at a particle inside an infinite cubic lattice whose spacing gives `mass` the rest density:
//   kappa = -V sum_j g(r_j) r_j^2 z_j^2 / (r_j^2 + 0.01 h^2),   V = mass / rho0
// (0.922 at h = 2s, 0.959 at 3s; engine/fixes/sph_viscosity.cpp divides its sum by it).
double lattice_laplacian(double mass, const Kernels& kernels, double rest_density);

}  // namespace pbf
