#pragma once
// The SPH kernel, Wendland C2 with support radius h (zero for r >= h), q = r / h:
//   W(r)  = c (1 - q)^4 (1 + 4q),          c = 21 / (2 pi h^3)
//   gradW = -20 c (1 - q)^3 / h^2 r_vec
// Every style takes densities, weights and gradients from this one kernel. A pressure or
// constraint force is then the gradient of the energy that the density sum implies, so the
// solvers do not feed energy into a fluid at rest; and the kernel's Fourier transform is
// positive, so pressure does not pair particles up (Dehnen & Aly 2012). docs/physics.md,
// "Kernels", has the measurements that chose it over Macklin & Mueller's poly6 densities with
// spiky gradients. It integrates to one over the support (tests/test_kernels.cpp).
#include <cmath>
#include <numbers>

#include "engine/core/real.hpp"

namespace pbf {

struct Kernels {
  real h, h2, inv_h, coef;

  explicit Kernels(double support)
      : h(real(support)),
        h2(real(support * support)),
        inv_h(real(1 / support)),
        coef(real(21.0 / (2.0 * std::numbers::pi * std::pow(support, 3)))) {}

  // W of the squared distance.
  real W(real r2) const {
    if (r2 >= h2) return 0;
    const real q = std::sqrt(r2) * inv_h, d = 1 - q;
    return coef * d * d * d * d * (1 + 4 * q);
  }

  // gradW = g(r) * r_vec; this returns g = -20 c (1 - q)^3 / h^2 (finite at r = 0, where the
  // kernel is smooth and the gradient vanishes with r_vec).
  real grad_factor(real r2) const {
    if (r2 >= h2) return 0;
    const real d = 1 - std::sqrt(r2) * inv_h;
    return -20 * coef * d * d * d * inv_h * inv_h;
  }

  // Both at once, with one square root (the density solvers' pair loops want both).
  void W_and_grad_factor(real r2, real& w, real& g) const {
    if (r2 >= h2) {
      w = g = 0;
      return;
    }
    const real q = std::sqrt(r2) * inv_h, d = 1 - q, d3 = d * d * d;
    w = coef * d3 * d * (1 + 4 * q);
    g = -20 * coef * d3 * inv_h * inv_h;
  }
};

}  // namespace pbf
