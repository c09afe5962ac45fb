#include "engine/fixes/inlet_zone.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>

#include "engine/core/parallel.hpp"
#include "engine/distributed/comm.hpp"

namespace pbf {

void InletZone::take(Particles& P, const Opening& opening, double behind, double depth, FieldId member) {
  clear();
  const real *x = P.x(), *y = P.y(), *z = P.z();
  real* in = P.data(member);
  for (std::size_t i = 0; i < P.size(); ++i) {  // serial: few particles pass, in index order
    if (in[i] == 0) continue;
    const auto o = opening.offset({double(x[i]), double(y[i]), double(z[i])});
    if (o[2] < -behind || o[2] >= depth || !opening.over(o[0], o[1], 0)) {
      in[i] = 0;
      continue;
    }
    index_.push_back(static_cast<std::uint32_t>(i));
    site_.push_back(static_cast<std::uint32_t>(opening.nearest_site(o[0], o[1])));
    start_.push_back({x[i], y[i], z[i]});
  }
}

void InletZone::find_back(Particles& P, const Opening& opening, double behind, double depth, FieldId member,
                          bool first, double L, std::vector<double>& D) const {
  D.assign(opening.sites(), std::numeric_limits<double>::infinity());
  const real *x = P.x(), *y = P.y(), *z = P.z();
  real* in = P.data(member);
  for (std::size_t i = 0; i < P.size(); ++i) {
    const auto o = opening.offset({double(x[i]), double(y[i]), double(z[i])});
    if (o[2] < -behind || o[2] >= depth || !opening.over(o[0], o[1], 0)) continue;
    if (first) in[i] = 1;  // the fluid the zone starts in
    if (in[i] == 0) continue;  // water that came in from beside: the zone pushes it out
    double& back = D[opening.nearest_site(o[0], o[1])];
    back = std::min(back, o[2]);
  }
  if (P.distributed()) comm::min(std::span<double>(D));
  for (double& d : D)
    if (std::isinf(d)) d = L;
}

void InletZone::move(Particles& P, const std::vector<std::array<real, 3>>& site_velocity, double dt,
                     bool with_velocity) const {
  real *x = P.x(), *y = P.y(), *z = P.z(), *vx = P.vx(), *vy = P.vy(), *vz = P.vz();
  for_particles(index_.size(), [&](std::size_t k) {
    const std::size_t i = index_[k];
    const auto& U = site_velocity[site_[k]];
    x[i] = real(double(start_[k][0]) + double(U[0]) * dt);
    y[i] = real(double(start_[k][1]) + double(U[1]) * dt);
    z[i] = real(double(start_[k][2]) + double(U[2]) * dt);
    if (!with_velocity) return;
    vx[i] = U[0];
    vy[i] = U[1];
    vz[i] = U[2];
  });
}

}  // namespace pbf
