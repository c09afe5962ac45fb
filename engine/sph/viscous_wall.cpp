#include "engine/sph/viscous_wall.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "engine/core/simulation.hpp"
#include "engine/sph/mass.hpp"

namespace pbf {

namespace {

constexpr int kIntervals = 1024;

// b(u) = 210 integral_u^1 (1 - q)^3 q^3 (q^2 - u^2) / (q^2 + 0.01) dq by Simpson's rule on 400
// intervals (a smooth integrand: its poles lie 0.1 off the real axis).
double b_integral(double u) {
  if (u >= 1) return 0;
  auto f = [u](double q) {
    const double v = 1 - q;
    return v * v * v * q * q * q * (q * q - u * u) / (q * q + 0.01);
  };
  const int n = 400;
  const double step = (1 - u) / n;
  double sum = f(u) + f(1);
  for (int k = 1; k < n; ++k) sum += (k % 2 ? 4 : 2) * f(u + k * step);
  return 210 * sum * step / 3;
}

// b at u = k / kIntervals, k = 0 .. kIntervals, computed once.
const std::array<double, kIntervals + 1>& b_table() {
  static const auto table = [] {
    std::array<double, kIntervals + 1> t{};
    for (int k = 0; k <= kIntervals; ++k) t[static_cast<std::size_t>(k)] = b_integral(double(k) / kIntervals);
    return t;
  }();
  return table;
}

double b_of(double u) {
  if (u >= 1) return 0;
  u = std::max(u, 0.0);
  const double at = u * kIntervals;
  const int k = std::min(static_cast<int>(at), kIntervals - 1);
  const double t = at - k;
  const auto& table = b_table();
  return (1 - t) * table[static_cast<std::size_t>(k)] + t * table[static_cast<std::size_t>(k) + 1];
}

}  // namespace

double NoSlipWall::share_of(double d) const {
  const double h = h_;
  return b_of((d + delta_) / h) / (h * std::max(d, h / 8));
}

real NoSlipWall::share(real d) const { return d < reach() ? real(share_of(d)) : real(0); }

void NoSlipWall::prepare(const Simulation& sim) {
  const double mass = sim.particle_mass();
  if (mass == 0) return;  // no particles yet: nothing to prepare for
  if (mass == prepared_[0] && sim.kernel_radius() == prepared_[1] && sim.rest_density() == prepared_[2]) return;
  prepared_[0] = mass;
  prepared_[1] = sim.kernel_radius();
  prepared_[2] = sim.rest_density();
  h_ = sim.kernels().h;
  const double spacing = lattice_spacing(mass, sim.kernels(), sim.rest_density());
  const double first = 0.5 * spacing;  // the first layer's distance from the surface
  const double missing = lattice_wall_shear(mass, sim.kernels(), sim.rest_density());
  // Psi falls with delta: bisect for the delta at which the first layer gets `missing` / d.
  double lo = -first, hi = sim.kernel_radius();
  for (int it = 0; it < 100; ++it) {
    delta_ = real(0.5 * (lo + hi));
    (share_of(first) * first > missing ? lo : hi) = 0.5 * (lo + hi);
  }
  delta_ = real(0.5 * (lo + hi));
}

}  // namespace pbf
