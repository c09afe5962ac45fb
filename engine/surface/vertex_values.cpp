// The particles' values at the surface's vertices: each vertex averages the particles whose
// kernels reach it, weighed by the kernel's value there (the weights phi sums), so the
// velocity on the surface is the velocity of the fluid that makes the surface there. A vertex
// no kernel reaches (the surface is phi = iso, so some kernel always does, but for one
// clamped onto a wall) takes its nearest particle's values. A mirror image's vector is the
// original's reflected.
#include <cmath>
#include <limits>

#include "engine/core/parallel.hpp"
#include "engine/surface/surface_parts.hpp"

namespace pbf {

void vertex_values(const SurfaceParticles& p, const std::vector<ParticleKernel>& kernels, const SurfaceCloud& cloud,
                   const NeighborGrid& cells, double radius, SurfacePiece& mesh) {
  const std::size_t nv = mesh.vertices.size(), n = cloud.size();
  mesh.attributes.clear();
  for (const auto& a : cloud.attributes)
    mesh.attributes.push_back({a.name, a.components, std::vector<double>(nv * static_cast<std::size_t>(a.components), 0.0)});
  if (cloud.attributes.empty() || nv == 0) return;
  const GridGeometry& g = cells.geometry();
  const std::uint32_t* starts = cells.cell_starts();
  const std::uint32_t* order = cells.sorted_order().data();
  const long* dims = g.dims;
  // (A little beyond R^2, so that no kernel whose d.Q.d rounds below 1 at R is left out.)
  const double beyond = 1.001 * radius * radius;
  for_blocks(nv, [&](std::size_t begin, std::size_t end) {
    std::vector<double> sum;
    for (std::size_t v = begin; v < end; ++v) {
      const auto& x = mesh.vertices[v];
      long c[3];
      for (int a = 0; a < 3; ++a) c[a] = g.cell_along(a, x[a]);
      double total = 0, nearest = std::numeric_limits<double>::infinity();
      std::uint32_t closest = 0;
      sum.assign(0, 0);
      for (const auto& a : cloud.attributes) sum.resize(sum.size() + static_cast<std::size_t>(a.components), 0.0);
      for (long cz = std::max(0L, c[2] - 1); cz <= std::min(dims[2] - 1, c[2] + 1); ++cz)
        for (long cy = std::max(0L, c[1] - 1); cy <= std::min(dims[1] - 1, c[1] + 1); ++cy)
          for (long cx = std::max(0L, c[0] - 1); cx <= std::min(dims[0] - 1, c[0] + 1); ++cx) {
            const std::size_t cell = static_cast<std::size_t>((cz * dims[1] + cy) * dims[0] + cx);
            for (std::uint32_t k = starts[cell]; k < starts[cell + 1]; ++k) {
              const std::uint32_t j = order[k];
              const double d[3] = {x[0] - p.x[j], x[1] - p.y[j], x[2] - p.z[j]};
              const double r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
              if (r2 < nearest) nearest = r2, closest = j;
              if (r2 > beyond) continue;  // outside every kernel: no semi-axis is longer than R
              const float* q = kernels[j].q;
              const double r = q[0] * d[0] * d[0] + q[1] * d[1] * d[1] + q[2] * d[2] * d[2] +
                               2 * (q[3] * d[0] * d[1] + q[4] * d[0] * d[2] + q[5] * d[1] * d[2]);
              if (r >= 1) continue;
              const double w = kernels[j].weight * (1 - r) * (1 - r) * (1 - r);
              total += w;
              std::size_t at = 0;
              for (const auto& a : cloud.attributes)
                for (int comp = 0; comp < a.components; ++comp, ++at) {
                  double value = a.values[static_cast<std::size_t>(comp) * n + p.source[j]];
                  if (a.components == 3 && ((p.flips[j] >> comp) & 1)) value = -value;
                  sum[at] += w * value;
                }
            }
          }
      std::size_t at = 0;
      for (std::size_t k = 0; k < cloud.attributes.size(); ++k) {
        const auto& a = cloud.attributes[k];
        for (int comp = 0; comp < a.components; ++comp, ++at) {
          double value;
          if (total > 0) {
            value = sum[at] / total;
          } else {
            value = a.values[static_cast<std::size_t>(comp) * n + p.source[closest]];
            if (a.components == 3 && ((p.flips[closest] >> comp) & 1)) value = -value;
          }
          mesh.attributes[k].values[static_cast<std::size_t>(comp) * nv + v] = value;
        }
      }
    }
  });
}

}  // namespace pbf
