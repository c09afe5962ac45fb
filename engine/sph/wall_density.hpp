#pragma once
// The density a flat wall adds: the wall counts as fluid at rest density filling the
// half-space behind it. For a particle at distance d < h from the wall, that fluid's share
// of the poly6 kernel is
//   f(d) = integral over {z > d + delta} of W dV = pi c / 4 (F(h) - F(d + delta)),
//   F(z) = integral (h^2 - z^2)^4 dz,   c = 315 / (64 pi h^9),
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
    const real zd = z > 0 ? (z < h_ ? z : h_) : 0;
    const real q = h2_ - zd * zd;
    slope = z > 0 && z < h_ ? -scale_ * q * q * q * q : 0;
    return scale_ * (F(h_) - F(zd));
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
  real delta() const { return delta_; }
  real kernel_radius() const { return h_; }

 private:
  real F(real z) const {
    const real z2 = z * z, h2 = h2_;
    return z * (h2 * h2 * h2 * h2 - z2 * (h2 * h2 * h2 * real(4.0 / 3) -
                                          z2 * (h2 * h2 * real(6.0 / 5) - z2 * (h2 * real(4.0 / 7) - z2 / 9))));
  }

  real h_ = 0, h2_ = 0, scale_ = 0, delta_ = 0;
  double prepared_[3] = {0, 0, 0};  // mass, h, rho0 that delta_ was computed for
};

}  // namespace pbf
