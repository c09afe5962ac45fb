#pragma once
// The viscous pull of a no-slip flat wall on a particle near it, for the Laplacian viscosity
// (Morris et al. 1997; engine/fixes/sph_viscosity.cpp). As for its density
// (engine/sph/wall_density.hpp), the wall counts as fluid filling the half-space behind it;
// for the viscosity that fluid moves as Morris's fictitious boundary particles do: the
// particle's velocity continued linearly through the wall's velocity v_w at the surface. A
// wall point at depth zeta behind the surface moves at
//   v_j = v_w - (zeta / d) (v_i - v_w),   d: particle i's distance from the surface,
// so v_i - v_j = (v_i - v_w) s_n / d, with s_n = d + zeta the normal separation. Morris's
// pair term nu' m_j (1/rho_i + 1/rho_j) (x_ij . gradW_ij) / (r^2 + eta^2) v_ij, with
// m_j / rho_j -> dV (the wall's fluid at rest density) and m_j / rho_i -> rho0 / rho_i dV,
// integrated over the wall's fluid (s_n > d + delta_v), is
//   a_i += nu' (1 + rho0 / rho_i) Psi(d) (v_w - v_i)_t,
// nu' the coefficient of the fluid's own sum (sph_viscosity's nu / kappa, the lattice factor
// divided out): the wall term stands for lattice sites, so it takes the same one.
//   Psi(d) = 1/d integral_{s_n > z0} (-g(r)) r^2 / (r^2 + eta^2) s_n dV
//          = pi / d integral_{z0}^{h} (-g(r)) r^3 (r^2 - z0^2) / (r^2 + eta^2) dr,   z0 = d + delta_v,
// (gradW = g r_vec, eta^2 = 0.01 h^2; on the sphere of radius r, the cap beyond the plane at
// z0 carries integral s_n dA = pi r (r^2 - z0^2)). With Wendland C2, q = r / h, u = z0 / h:
//   Psi(d) = b(u) / (h d),   b(u) = 210 integral_u^1 (1 - q)^3 q^3 (q^2 - u^2) / (q^2 + 0.01) dq,
// tabulated once (Simpson) on 1024 intervals of u and read linearly (relative error ~1e-7).
// Only the tangential part, (w)_t = w - (w . n) n with n the wall's normal: the continuation is
// that of the velocity along the wall; the normal velocity, held by the wall's pressure and
// projection, has no zero crossing at the surface to continue (at a no-slip wall dv_n/dn =
// -div_t v_t = 0), and a linear continuation would damp every approach to a wall.
// A linear shear above the wall is then continued exactly, and its SPH Laplacian is zero at
// the wall layers as in the bulk; a parabola's curvature is not continued, so the first layer
// sees 1 - eps of its Laplacian, eps(d) = integral_wall (-g) r^2/(r^2+eta^2) s_n (s_n - d) dV
// over the full second moment (0.25 on the lattice at d = s/2, h = 2s), a force at the wall
// that moves a Poiseuille centre line by 4 eps z' s / H^2 only (docs/physics.md). The
// continuum also reaches the second layer (d = 3s/2) within h - delta_v, where no lattice
// site behind the wall does: a sliver, 1.3% of the first layer's share.
// delta_v is chosen, as the density's delta, so that a particle of the initial lattice's
// first layer (d = s/2) gets exactly what the lattice sites behind the wall would give a
// linear shear (0.013 s at h = 2s). A particle closer than h/8 (only with a contact
// distance below 1/4 spacing at h = 2s) is taken at h/8: Psi grows as 1/d, and the cap keeps
// the wall's rate nu' (1 + rho0/rho) Psi within the viscous time-step limit of cfl (cfl's step
// 0.125 (h/2)^2 / nu times the rate is about 0.5 b(1/8 + delta_v/h) / kappa = 0.69 at h = 2s).
#include "engine/core/real.hpp"

namespace pbf {

class Simulation;

class NoSlipWall {
 public:
  // Brings h and delta_v up to date with the scene's h, particle mass and rest density;
  // cheap when nothing changed.
  void prepare(const Simulation& sim);

  // Psi(d) (1/m^2) at distance d from the surface; 0 beyond the kernel's reach.
  real share(real d) const;
  // Beyond this distance from the surface, Psi = 0.
  real reach() const { return h_ - delta_; }

 private:
  double share_of(double d) const;  // in double, for prepare's bisection
  real h_ = 0, delta_ = 0;
  double prepared_[3] = {0, 0, 0};  // mass, h, rho0 that delta_ was computed for
};

}  // namespace pbf
