#include "engine/sph/velocity_curl.hpp"

#include "engine/core/simulation.hpp"
#include "engine/sph/pair_sums.hpp"

namespace pbf {

void velocity_curl(Simulation& sim, const std::vector<real>& volume, real* wx, real* wy, real* wz, real* magnitude) {
  const auto& P = sim.particles();
  const PairInput pairs{sim.neighbors(), P.x(), P.y(), P.z(), P.mass(), 0, sim.kernels(), P.size()};
  curl_sums(pairs, volume.data(), P.vx(), P.vy(), P.vz(), wx, wy, wz, magnitude);
}

}  // namespace pbf
