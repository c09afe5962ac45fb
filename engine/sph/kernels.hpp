#pragma once
// SPH kernels with support radius h (zero for r >= h):
//   poly6  W(r)  = 315 / (64 pi h^9) (h^2 - r^2)^3             (density, weights)
//   spiky  gradW = -45 / (pi h^6) (h - r)^2 r_vec / r          (gradients; no zero at r -> 0)
//   Wendland C2  W(r) = 21 / (2 pi h^3) (1 - q)^4 (1 + 4q), q = r / h   (WCSPH forces)
// All are normalised to integrate to one over the support (tests/test_kernels.cpp).
#include <cmath>
#include <numbers>

#include "engine/core/real.hpp"

namespace pbf {

struct Kernels {
  real h, h2, poly6_coef, spiky_coef, wendland_coef;

  explicit Kernels(double support)
      : h(real(support)),
        h2(real(support * support)),
        poly6_coef(real(315.0 / (64.0 * std::numbers::pi * std::pow(support, 9)))),
        spiky_coef(real(45.0 / (std::numbers::pi * std::pow(support, 6)))),
        wendland_coef(real(21.0 / (2.0 * std::numbers::pi * std::pow(support, 3)))) {}

  // poly6 of the squared distance.
  real poly6(real r2) const {
    if (r2 >= h2) return 0;
    const real d = h2 - r2;
    return poly6_coef * d * d * d;
  }

  // The spiky gradient is gradW = g(r) * r_vec; this returns g (zero at r = 0 and r >= h).
  real spiky_grad_factor(real r2) const {
    if (r2 >= h2 || r2 <= 0) return 0;
    const real r = std::sqrt(r2);
    const real d = h - r;
    return -spiky_coef * d * d / r;
  }

  // Wendland C2 of the distance r.
  real wendland(real r) const {
    if (r >= h) return 0;
    const real q = r / h, d = 1 - q;
    return wendland_coef * d * d * d * d * (1 + 4 * q);
  }

  // The Wendland C2 gradient is gradW = g(r) * r_vec; this returns g = -20 c (1 - q)^3 / h^2
  // (finite at r = 0: the kernel is smooth there, so the gradient vanishes with r_vec).
  real wendland_grad_factor(real r2) const {
    if (r2 >= h2) return 0;
    const real q = std::sqrt(r2) / h, d = 1 - q;
    return -20 * wendland_coef * d * d * d / h2;
  }

  // The spiky kernel itself, 15 / (pi h^6) (h - r)^3, for normalisation checks.
  real spiky(real r) const {
    if (r >= h) return 0;
    const real d = h - r;
    return spiky_coef / 3 * d * d * d;
  }
};

}  // namespace pbf
