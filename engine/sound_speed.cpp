#include "engine/sound_speed.hpp"

#include <algorithm>
#include <cmath>

#include "engine/mass.hpp"
#include "engine/parallel.hpp"
#include "engine/simulation.hpp"

namespace pbf {

double default_sound_speed(const Simulation& sim, double gravity) {
  const auto& P = sim.particles();
  const std::size_t n = P.size();
  if (n == 0) return 0;
  double lo = P.z()[0], hi = P.z()[0];
  for (std::size_t i = 0; i < n; ++i) lo = std::min(lo, double(P.z()[i])), hi = std::max(hi, double(P.z()[i]));
  const double mass = deterministic_sum(n, [&](std::size_t i) { return double(P.mass()[i]); }) / double(n);
  const double height = hi - lo + lattice_spacing(mass, sim.kernels(), sim.rest_density());
  return 10 * std::sqrt(2 * std::fabs(gravity) * height);
}

}  // namespace pbf
