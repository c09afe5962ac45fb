#include "engine/velocity_curl.hpp"

#include <cmath>

#include "engine/simulation.hpp"

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
    const std::uint32_t* nb = grid.neighbors(i);
    for (std::uint32_t k = 0; k < grid.count(i); ++k) {
      const std::uint32_t j = nb[k];
      const real dx = x[i] - x[j], dy = y[i] - y[j], dz = z[i] - z[j];
      const real g = m[j] / rho[j] * K.spiky_grad_factor(dx * dx + dy * dy + dz * dz);
      const real gx = g * dx, gy = g * dy, gz = g * dz;
      const real ux = vx[j] - vx[i], uy = vy[j] - vy[i], uz = vz[j] - vz[i];
      w[0] += gy * uz - gz * uy;
      w[1] += gz * ux - gx * uz;
      w[2] += gx * uy - gy * ux;
    }
    wx[i] = w[0];
    wy[i] = w[1];
    wz[i] = w[2];
    magnitude[i] = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
  }
}

}  // namespace pbf
