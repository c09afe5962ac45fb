// The kernels integrate to one over their support, and the spiky gradient is the
// derivative of the spiky kernel.
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

TEST(Kernels, Poly6IntegratesToOne) {
  for (double h : {0.01, 0.04, 1.0, 3.0}) {
    const Kernels K(h);
    EXPECT_NEAR(radial_integral(h, [&](double r) { return double(K.poly6(real(r * r))); }), 1.0, 1e-6) << "h = " << h;
  }
}

TEST(Kernels, SpikyIntegratesToOne) {
  for (double h : {0.02, 1.0}) {
    const Kernels K(h);
    EXPECT_NEAR(radial_integral(h, [&](double r) { return double(K.spiky(real(r))); }), 1.0, 1e-6);
  }
}

TEST(Kernels, SpikyGradientIsTheDerivative) {
  const double h = 0.05;
  const Kernels K(h);
  for (double q : {0.1, 0.3, 0.5, 0.8, 0.95}) {
    const double r = q * h, e = (sizeof(real) == 4 ? 1e-3 : 1e-7) * h;  // above the type's rounding
    const double derivative = (K.spiky(real(r + e)) - K.spiky(real(r - e))) / (2 * e);
    // gradW = factor * r_vec, so dW/dr = factor * r
    EXPECT_NEAR(K.spiky_grad_factor(real(r * r)) * r, derivative, 1e3 * pbf::test::kRounding * std::fabs(derivative))
        << "r/h = " << q;
  }
}

TEST(Kernels, ZeroOutsideTheSupport) {
  const Kernels K(0.1);
  EXPECT_EQ(K.poly6(real(0.0101)), 0);
  EXPECT_EQ(K.poly6(real(0.02)), 0);
  EXPECT_EQ(K.spiky_grad_factor(real(0.0101)), 0);
  EXPECT_EQ(K.spiky_grad_factor(0), 0);  // no direction at r = 0
  EXPECT_GT(K.poly6(real(0.0099)), 0);
}

TEST(Kernels, WendlandIntegratesToOneAndItsGradientIsTheDerivative) {
  for (double h : {0.02, 1.0}) {
    const Kernels K(h);
    EXPECT_NEAR(radial_integral(h, [&](double r) { return double(K.wendland(real(r))); }), 1.0, 1e-6) << h;
    for (double q : {0.1, 0.3, 0.5, 0.8, 0.95}) {
      const double r = q * h, e = (sizeof(real) == 4 ? 1e-3 : 1e-7) * h;
      const double derivative = (K.wendland(real(r + e)) - K.wendland(real(r - e))) / (2 * e);
      EXPECT_NEAR(K.wendland_grad_factor(real(r * r)) * r, derivative,
                  1e3 * pbf::test::kRounding * std::fabs(derivative))
          << "r/h = " << q;
    }
    EXPECT_EQ(K.wendland(real(h)), 0);
    EXPECT_EQ(K.wendland_grad_factor(real(h * h)), 0);
  }
}
