#include "engine/sph/velocity_curl.hpp"

#include "engine/core/parallel.hpp"
#include "engine/core/simulation.hpp"
#include "engine/sph/pair_sums.hpp"

namespace pbf {

void velocity_curl(Simulation& sim, const std::vector<real>& volume, real* wx, real* wy, real* wz, real* magnitude) {
  const auto& P = sim.particles();
  const PairInput pairs{sim.neighbors(), P.x(), P.y(), P.z(), P.mass(), 0, sim.kernels(), P.size()};
  for_blocks(P.size(), [&](std::size_t begin, std::size_t end) {
    curl_sums(pairs, begin, end, volume.data(), P.vx(), P.vy(), P.vz(), wx, wy, wz, magnitude);
  });
}

}  // namespace pbf
