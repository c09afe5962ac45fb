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
    EXPECT_NEAR(radial_integral(h, [&](double r) { return double(K.W(real(r * r))); }), 1.0, 1e-6) << h;
    for (double q : {0.1, 0.3, 0.5, 0.8, 0.95}) {
      const double r = q * h, e = (sizeof(real) == 4 ? 1e-3 : 1e-7) * h;  // above the type's rounding
      const double derivative = (K.W(real((r + e) * (r + e))) - K.W(real((r - e) * (r - e)))) / (2 * e);
      // gradW = factor * r_vec, so dW/dr = factor * r
      EXPECT_NEAR(K.grad_factor(real(r * r)) * r, derivative, 1e3 * pbf::test::kRounding * std::fabs(derivative))
          << "r/h = " << q;
      real w, g;
      K.W_and_grad_factor(real(r * r), w, g);
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
