#include "engine/sph/velocity_curl.hpp"

#include <cmath>

#include "engine/core/simulation.hpp"

namespace pbf {

void velocity_curl(Simulation& sim, const std::vector<real>& rho, real* wx, real* wy, real* wz, real* magnitude) {
  const auto& P = sim.particles();
  const auto& grid = sim.neighbors();
  const Kernels& K = sim.kernels();
  const std::size_t n = P.size();
  const real *x = P.x(), *y = P.y(), *z = P.z(), *m = P.mass();
  const real *vx = P.vx(), *vy = P.vy(), *vz = P.vz();
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    real w[3] = {0, 0, 0};
    grid.for_each_neighbor(i, x, y, z, [&](std::uint32_t j, real dx, real dy, real dz, real r2) {
      const real g = m[j] / rho[j] * K.grad_factor(r2);
      const real gx = g * dx, gy = g * dy, gz = g * dz;
      const real ux = vx[j] - vx[i], uy = vy[j] - vy[i], uz = vz[j] - vz[i];
      w[0] += gy * uz - gz * uy;
      w[1] += gz * ux - gx * uz;
      w[2] += gx * uy - gy * ux;
    });
    wx[i] = w[0];
    wy[i] = w[1];
    wz[i] = w[2];
    magnitude[i] = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
  }
}

}  // namespace pbf
