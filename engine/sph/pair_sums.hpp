#pragma once
// The neighbour sums of the SPH styles, vectorised across the neighbours of a particle
// (engine/sph/pair_sums.cpp). The equations are those at the top of the style that calls each
// sum; here they are only computed. Each function computes the particles [begin, end) and
// opens no parallel region: the style calls it from its own (for_blocks,
// engine/core/parallel.hpp) and does the per-particle work that follows a block's sums in the
// same region, while the block is in cache and without another meeting of the threads.
//
// Bits: lane k of a sum collects the terms k, k + 16, k + 32, ... of a particle's list (8 in
// double precision), and the lanes are added in one fixed tree, whatever the machine's vector
// width: a sum has the same bits at any thread count and on any x86-64 machine
// (docs/design.md, "Vectors").
#include <cstddef>

#include "engine/core/real.hpp"
#include "engine/sph/kernels.hpp"

namespace pbf {

class NeighborGrid;

// What every pass reads: the lists, positions, masses and the kernel. `uniform_mass` is the
// mass of every particle when all have the same (0 when they differ): the passes then need
// not gather it (uniform_mass() says which). n: the particles with lists.
struct PairInput {
  const NeighborGrid& grid;
  const real *x, *y, *z, *m;
  real uniform_mass;
  const Kernels& kernels;
  std::size_t n;
};

// The particles' common mass, or 0 when the masses differ.
real uniform_mass(const real* m, std::size_t n, bool across_ranks = false);

// rho_i = m_i W(0) + sum_j m_j W_ij (the fluid's share of the SPH density).
void density_sums(const PairInput& in, std::size_t begin, std::size_t end, real* rho);

// PBF's density pass: rho as above; with g_j = m_j / rho0 * (gradW_ij / r_ij),
// grad_i = sum_j g_j r_ij (the gradient of C_i with respect to x_i, fluid part) and
// grad_sq_i = sum_j g_j^2 |r_ij|^2 (the sum over neighbours of |grad_j C_i|^2).
void constraint_sums(const PairInput& in, std::size_t begin, std::size_t end, real inv_rho0, real* rho, real* grad_x,
                     real* grad_y, real* grad_z, real* grad_sq);

// PBF's correction: d_i = inv_rho0 sum_j m_j (lambda_i + lambda_j + s_ij) gradW_ij, with
// s_ij = -scorr_scale (W_ij * inv_wdq)^scorr_n (none when scorr_scale is 0).
void constraint_corrections(const PairInput& in, std::size_t begin, std::size_t end, const real* lambda, real inv_rho0,
                            real scorr_scale, real inv_wdq, int scorr_n, real* dx, real* dy, real* dz);

// The rate at which a velocity field u changes the density (the continuity equation's sum):
// out_i = sum_j m_j (u_i - u_j) . gradW_ij.
void divergence_sums(const PairInput& in, std::size_t begin, std::size_t end, const real* ux, const real* uy,
                     const real* uz, real* out);

// The sums below weigh neighbour j by its volume V_j = m_j / rho_j (`volume`; the masses of
// PairInput are not read).

// The curl of the velocity: w_i = sum_j V_j gradW_ij x (v_j - v_i), and |w_i|.
void curl_sums(const PairInput& in, std::size_t begin, std::size_t end, const real* volume, const real* vx,
               const real* vy, const real* vz, real* wx, real* wy, real* wz, real* magnitude);

// The gradient of a scalar f: e_i = sum_j V_j (f_j - f_i) gradW_ij.
void gradient_sums(const PairInput& in, std::size_t begin, std::size_t end, const real* volume, const real* f, real* ex,
                   real* ey, real* ez);

// The velocity's smoothing: d_i = sum_j V_j (v_j - v_i) W_ij.
void smoothing_sums(const PairInput& in, std::size_t begin, std::size_t end, const real* volume, const real* vx,
                    const real* vy, const real* vz, real* dx, real* dy, real* dz);

}  // namespace pbf
