// reconstruct_surface: the settings checked, then the steps of engine/surface/surface_parts.hpp.
#include "engine/surface/surface.hpp"

#include <chrono>
#include <cmath>

#include <fmt/format.h>

#include "engine/core/error.hpp"
#include "engine/surface/surface_parts.hpp"

namespace pbf {

void check_surface_input(const SurfaceCloud& cloud, const SurfaceSettings& s) {
  auto positive = [](const char* name, double v, const char* unit) {
    if (!(std::isfinite(v) && v > 0)) throw Error(fmt::format("surface: '{}' must be a positive {}, got {}", name, unit, v));
  };
  positive("spacing", s.spacing, "length (m)");
  positive("radius", s.radius, "length (m)");
  positive("voxel", s.voxel, "length (m)");
  positive("memory", s.memory_limit, "number of bytes");
  if (!(std::isfinite(s.iso) && s.iso > 0 && s.iso < 1))
    throw Error(fmt::format("surface: 'iso' must lie between 0 and 1 (phi is 1 inside the fluid), got {}", s.iso));
  if (s.kernel == SurfaceKernel::spheres) positive("sphere_radius", s.sphere_radius, "length (m)");
  if (!(s.max_stretch >= 1 && std::isfinite(s.max_stretch)))
    throw Error(fmt::format("surface: 'max_stretch' must be at least 1, got {}", s.max_stretch));
  for (int a = 0; a < 3; ++a)
    if (!(s.hi[a] > s.lo[a])) throw Error("surface: the domain is empty");
  const std::size_t n = cloud.size();
  if (cloud.y.size() != n || cloud.z.size() != n || cloud.volume.size() != n)
    throw Error("surface: positions and volumes differ in length");
  for (const auto& a : cloud.attributes)
    if (a.values.size() != n * static_cast<std::size_t>(a.components))
      throw Error(fmt::format("surface: attribute '{}' has {} values for {} particles", a.name, a.values.size(), n));
  for (std::size_t i = 0; i < n; ++i)
    if (!(std::isfinite(cloud.x[i]) && std::isfinite(cloud.y[i]) && std::isfinite(cloud.z[i]) &&
          std::isfinite(cloud.volume[i]) && cloud.volume[i] >= 0))
      throw Error(fmt::format("surface: particle {} (of {}) has a position or volume that is not finite", i, n));
  for (const auto& m : cloud.mirrors) {
    const double length = std::hypot(m.normal[0], m.normal[1], m.normal[2]);
    if (!(m.particle < n && std::fabs(length - 1) < 1e-6 && std::isfinite(m.distance) && m.distance >= 0))
      throw Error(fmt::format("surface: the mirror of particle {} has no particle, a normal that is not a unit "
                              "vector, or a distance that is not a finite positive length",
                              m.particle));
  }
}

namespace {

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

SurfacePiece reconstruct_surface_part(const SurfaceCloud& cloud, const SurfaceSettings& settings,
                                      const SurfacePart& part, SurfaceStats* stats_out) {
  check_surface_input(cloud, settings);
  SurfaceStats stats;
  auto t = std::chrono::steady_clock::now();
  const SurfaceParticles particles = with_images(cloud, settings);
  NeighborGrid cells;
  const std::vector<ParticleKernel> kernels = particle_kernels(particles, cloud, settings, cells);
  stats.images = particles.size() - particles.originals;
  stats.seconds_kernels = seconds_since(t);

  const VoxelBlocks field = voxel_blocks(particles, kernels, settings, part, stats);

  t = std::chrono::steady_clock::now();
  SurfacePiece piece = march_blocks(field, settings, part);
  stats.seconds_mesh = seconds_since(t);

  t = std::chrono::steady_clock::now();
  for (const auto& a : cloud.attributes) piece.attributes.push_back({a.name, a.components, {}});
  if (!cloud.attributes.empty()) vertex_values(particles, kernels, cloud, cells, settings.radius, piece);
  stats.seconds_attributes = seconds_since(t);
  if (stats_out) *stats_out = stats;
  return piece;
}

SurfaceMesh reconstruct_surface(const SurfaceCloud& cloud, const SurfaceSettings& settings, SurfaceStats* stats_out) {
  std::vector<SurfacePiece> piece;
  piece.push_back(reconstruct_surface_part(cloud, settings, SurfacePart{}, stats_out));
  const auto t = std::chrono::steady_clock::now();
  SurfaceMesh mesh = join_surface_pieces(piece, settings);
  if (stats_out) {
    stats_out->seconds_mesh += seconds_since(t);
    stats_out->bytes += mesh.mesh.vertices.size() * (sizeof(mesh.mesh.vertices[0]) + sizeof(mesh.normals[0])) +
                        mesh.mesh.triangles.size() * sizeof(mesh.mesh.triangles[0]);
  }
  return mesh;
}

}  // namespace pbf
