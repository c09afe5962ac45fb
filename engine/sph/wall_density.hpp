#pragma once
// The density a flat wall adds: the wall counts as fluid at rest density filling the
// half-space behind it. For a particle at distance d < h from the wall, that fluid's share
// of the kernel (Wendland C2, engine/sph/kernels.hpp) is, with u = (d + delta) / h,
//   f(d) = integral over {z > d + delta} of W dV = 2 pi integral_z^h W(r) r (r - z) dr
//        = 1/2 - 3/2 u + 7/2 u^3 - 21/2 u^5 + 14 u^6 - 15/2 u^7 + 3/2 u^8,
//   df/dd = 3 / (2h) (u - 1)^5 (8 u^2 + 5 u + 1),
// with delta (a small fraction of the spacing) chosen so that a particle of the initial
// lattice's first layer, half a spacing from the wall, sees exactly the density of the
// lattice sites it misses. The box fix uses it for each face; a solid of any shape uses it
// for its local tangent plane and corrects for the curvature (engine/geometry/solid_map.hpp).
#include "engine/core/real.hpp"

namespace pbf {

class Simulation;

class HalfSpaceWall {
 public:
  // Brings h and delta up to date with the scene's h, particle mass and rest density;
  // cheap when nothing changed. Returns true when they changed.
  bool prepare(const Simulation& sim);

  // f(d), the fraction of a full neighbourhood behind a wall at distance d (0 <= f <= 1/2
  // for d >= -delta; 1/2 closer than that), and df/dd in `slope` (<= 0).
  real fraction(real d, real& slope) const {
    const real z = d + delta_;
    const real u = z > 0 ? (z < h_ ? z * inv_h_ : 1) : 0;
    const real v = u - 1, v2 = v * v;
    slope = z > 0 && z < h_ ? real(1.5) * inv_h_ * v2 * v2 * v * (u * (8 * u + 5) + 1) : 0;
    return real(0.5) +
           u * (real(-1.5) + u * u * (real(3.5) + u * u * (real(-10.5) + u * (14 + u * (real(-7.5) + u * real(1.5))))));
  }
  // The same continued behind the wall's fluid surface (d < -delta), where the wall fills
  // more than half the neighbourhood: 1 - f of the mirror point. Strictly decreasing on
  // (-h - delta, h - delta), so a solid's map can invert it.
  real fraction_both_sides(real d, real& slope) const {
    const real z = d + delta_;
    if (z >= 0) return fraction(d, slope);
    const real share = fraction(-z - delta_, slope);  // the mirror point, at z -> -z
    return 1 - share;
  }
  // The moments of the wall's fluid, for a pressure that varies through it (the hydrostatic
  // pressure a mirrored wall carries, engine/fixes/dfsph.cpp): with q = y - x the vector from
  // the particle to a point y of the wall's fluid and n the wall's normal,
  //   integral over the wall's fluid of gradW(x - y) (x) q dV = A(d) n n + B(d) (1 - n n),
  //   A = -2 pi / 3 integral_z^h W'(r) (r^3 - z^3) dr,
  //   B = -pi integral_z^h W'(r) (2 r^3 / 3 - z r^2 + z^3 / 3) dr,   z = d + delta,
  // (1/2 each at z = 0; the whole space around x gives 1; B is f itself, by parts along the
  // wall, so a wall's support along it is its density). The integrands are polynomials of
  // degree 7: five Gauss-Legendre points are exact.
  void moments(real d, real& normal, real& tangential) const;
  real delta() const { return delta_; }
  real kernel_radius() const { return h_; }

 private:
  real h_ = 0, inv_h_ = 0, delta_ = 0;
  double prepared_[3] = {0, 0, 0};  // mass, h, rho0 that delta_ was computed for
};

}  // namespace pbf
