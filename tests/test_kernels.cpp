// The kernel integrates to one over its support, its gradient is its derivative, and the
// two are zero outside the support.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "engine/sph/kernels.hpp"
#include "test_util.hpp"

using pbf::Kernels;
using pbf::real;

namespace {

// integral over the ball of radius h of f(r) dV, by the midpoint rule on shells.
template <class F>
double radial_integral(double h, F&& f) {
  const int n = 200000;
  double sum = 0;
  for (int k = 0; k < n; ++k) {
    const double r = (k + 0.5) * h / n;
    sum += 4 * std::numbers::pi * r * r * f(r) * h / n;
  }
  return sum;
}

}  // namespace

TEST(Kernels, IntegratesToOneAndItsGradientIsTheDerivative) {
  for (double h : {0.01, 0.02, 1.0, 3.0}) {
    const Kernels K(h);
    // Each W(r) errs by a few u of real (6e-8 in single precision), so the sum does; the midpoint
    // rule's error is (h/n)^2-small (1e-11). A constant off by 0.1% fails 1e-6 a thousand times over.
    EXPECT_NEAR(radial_integral(h, [&](double r) { return double(K.W(real(r * r))); }), 1.0, 1e-6) << h;
    for (double q : {0.1, 0.3, 0.5, 0.8, 0.95}) {
      const double r = q * h, e = (sizeof(real) == 4 ? 1e-3 : 1e-7) * h;  // above the type's rounding
      const double derivative = (K.W(real((r + e) * (r + e))) - K.W(real((r - e) * (r - e)))) / (2 * e);
      // gradW = factor * r_vec, so dW/dr = factor * r. The central difference errs by
      // e^2 |W'''| / 6 (1e-6 relative) and by u W / e of rounding (6e-5 relative in single
      // precision): 1e3 kRounding is 0.1% there (1e-6 in double); a wrong exponent or constant is O(1).
      EXPECT_NEAR(K.grad_factor(real(r * r)) * r, derivative, 1e3 * pbf::test::kRounding * std::fabs(derivative))
          << "r/h = " << q;
      real w, g;
      K.W_and_grad_factor(real(r * r), w, g);
      // The same formula computed another way: a few u apart at most (10 kRounding is far above).
      EXPECT_NEAR(w, K.W(real(r * r)), 10 * pbf::test::kRounding * w);
      EXPECT_NEAR(g, K.grad_factor(real(r * r)), 10 * pbf::test::kRounding * std::fabs(g));
    }
  }
}

TEST(Kernels, ZeroOutsideTheSupport) {
  const Kernels K(0.1);
  EXPECT_EQ(K.W(real(0.0101)), 0);
  EXPECT_EQ(K.W(real(0.01)), 0);
  EXPECT_EQ(K.grad_factor(real(0.0101)), 0);
  EXPECT_EQ(K.grad_factor(real(0.01)), 0);
  EXPECT_GT(K.W(real(0.0099)), 0);
  EXPECT_LT(K.grad_factor(0), 0);  // finite at r = 0, where the gradient vanishes with r_vec
}
