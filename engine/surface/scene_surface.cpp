#include "engine/surface/scene_surface.hpp"

#include <algorithm>
#include <cstring>

#include "engine/core/simulation.hpp"
#include "engine/distributed/comm.hpp"
#include "engine/sph/mass.hpp"

namespace pbf {

SurfaceSettings scene_surface_settings(Simulation& sim, double voxel_spacings, double radius_spacings) {
  SurfaceSettings s;
  const double mass = sim.particle_mass();  // collective
  s.spacing = mass > 0 ? lattice_spacing(mass, sim.kernels(), sim.rest_density()) : sim.kernel_radius() / 2;
  s.mass = mass;
  s.radius = radius_spacings * s.spacing;
  s.voxel = voxel_spacings * s.spacing;
  s.sphere_radius = 0.6 * s.spacing;
  const Domain& d = sim.domain();
  for (int a = 0; a < 3; ++a) {
    s.lo[a] = d.lo[a], s.hi[a] = d.hi[a];
    for (int side = 0; side < 2; ++side) s.wall[2 * a + side] = !d.periodic[a] && !d.open[2 * a + side];
  }
  return s;
}

SurfaceCloud scene_cloud(Simulation& sim, DumpFields& fields, const SurfaceSettings& settings) {
  if (sim.particles().distributed()) sim.refresh_neighbors();  // derived fields read neighbours
  const auto& P = sim.particles();
  const std::size_t n = P.size();
  std::vector<std::vector<const real*>> columns;
  std::size_t width = 5;  // id, x, y, z, mass, then each field's components
  for (std::size_t k = 0; k < fields.size(); ++k) {
    columns.push_back(fields.columns(sim, k));
    width += columns.back().size();
  }
  std::vector<double> mine(n * width);
  for (std::size_t i = 0; i < n; ++i) {
    double* r = &mine[i * width];
    r[0] = static_cast<double>(P.ids()[i]), r[1] = P.x()[i], r[2] = P.y()[i], r[3] = P.z()[i], r[4] = P.mass()[i];
    std::size_t at = 5;
    for (const auto& field : columns)
      for (const real* c : field) r[at++] = c[i];
  }
  std::vector<double> all;
  if (P.distributed()) {
    const auto gathered = comm::gather_bytes(
        std::span<const char>(reinterpret_cast<const char*>(mine.data()), mine.size() * sizeof(double)));
    for (const auto& bytes : gathered) {
      const std::size_t old = all.size();
      all.resize(old + bytes.size() / sizeof(double));
      std::memcpy(all.data() + old, bytes.data(), bytes.size());
    }
  } else {
    all = std::move(mine);
  }
  const std::size_t total = all.size() / width;
  std::vector<std::size_t> order(total);
  for (std::size_t i = 0; i < total; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return all[a * width] < all[b * width]; });
  SurfaceCloud c;
  c.x.resize(total), c.y.resize(total), c.z.resize(total), c.volume.resize(total);
  const double unit = settings.spacing * settings.spacing * settings.spacing / (settings.mass > 0 ? settings.mass : 1);
  for (std::size_t k = 0; k < fields.size(); ++k)
    c.attributes.push_back({fields.names()[k], static_cast<int>(columns[k].size()),
                            std::vector<double>(total * columns[k].size())});
  for (std::size_t i = 0; i < total; ++i) {
    const double* r = &all[order[i] * width];
    c.x[i] = static_cast<real>(r[1]), c.y[i] = static_cast<real>(r[2]), c.z[i] = static_cast<real>(r[3]);
    c.volume[i] = r[4] * unit;
    std::size_t at = 5;
    for (auto& a : c.attributes)
      for (int comp = 0; comp < a.components; ++comp) a.values[static_cast<std::size_t>(comp) * total + i] = r[at++];
  }
  return c;
}

}  // namespace pbf
