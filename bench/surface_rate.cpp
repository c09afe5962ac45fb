// surface_rate: how fast the engine meshes a frame of particles (engine/surface), and with how
// much memory: the figures of docs/performance/surface.md.
//
//   build/bench/surface_rate FRAME --spacing S [--voxel 0.5] [--radius 2] [--kernel anisotropic]
//                            [--repeats 3] [--threads T] [--ply OUT.ply] [--domain X0 Y0 Z0 X1 Y1 Z1]
//
// FRAME: a text file, "x y z" (m) per particle (a dump/text frame's first three columns), lines
// that are not three numbers ignored (share/benchmarks/surface_rate.sh
// makes one of the dam break). Voxel and radius are in spacings. Prints each step's time (the
// median of the repeats), particles per core-second (particles / (seconds x threads)), the
// mesh's size, the memory the reconstruction says it held and the process's peak resident set
// (VmHWM), and a hash of the mesh, which is the same at any thread count.
#include <omp.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "engine/io/surface_files.hpp"
#include "engine/surface/surface.hpp"

namespace {

double peak_rss_mib() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) / 1024;
  return 0;
}

std::uint64_t mesh_hash(const pbf::SurfaceMesh& m) {
  std::uint64_t h = 14695981039346656037ull;
  auto mix = [&](const void* data, std::size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t k = 0; k < bytes; ++k) h = (h ^ p[k]) * 1099511628211ull;
  };
  mix(m.mesh.vertices.data(), m.mesh.vertices.size() * sizeof(m.mesh.vertices[0]));
  mix(m.mesh.triangles.data(), m.mesh.triangles.size() * sizeof(m.mesh.triangles[0]));
  mix(m.normals.data(), m.normals.size() * sizeof(m.normals[0]));
  return h;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: surface_rate FRAME --spacing S [--voxel 0.5] [--radius 2] [--kernel K] "
                         "[--repeats 3] [--threads T] [--ply OUT]\n");
    return 2;
  }
  std::string frame = argv[1], kernel = "anisotropic", ply;
  double spacing = 0, voxel = 0.5, radius = 2;
  int smoothing = -1;
  int repeats = 3, threads = omp_get_max_threads();
  std::vector<double> domain;
  for (int k = 2; k + 1 < argc; k += 2) {
    const std::string flag = argv[k], value = argv[k + 1];
    if (flag == "--domain" && k + 6 < argc) {
      for (int c = 1; c <= 6; ++c) domain.push_back(std::stod(argv[k + c]));
      k += 5;
      continue;
    }
    if (flag == "--spacing") spacing = std::stod(value);
    else if (flag == "--voxel") voxel = std::stod(value);
    else if (flag == "--radius") radius = std::stod(value);
    else if (flag == "--kernel") kernel = value;
    else if (flag == "--repeats") repeats = std::stoi(value);
    else if (flag == "--threads") threads = std::stoi(value);
    else if (flag == "--ply") ply = value;
    else if (flag == "--smoothing") smoothing = std::stoi(value);
    else {
      std::fprintf(stderr, "surface_rate: unknown option %s\n", flag.c_str());
      return 2;
    }
  }
  if (!(spacing > 0)) {
    std::fprintf(stderr, "surface_rate: --spacing S (m) is required\n");
    return 2;
  }
  pbf::SurfaceCloud cloud;
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  {
    std::ifstream in(frame);
    if (!in) {
      std::fprintf(stderr, "surface_rate: cannot read %s\n", frame.c_str());
      return 1;
    }
    std::string line;
    while (std::getline(in, line)) {
      if (line.empty() || line[0] == '#') continue;
      std::istringstream row(line);
      double p[3];
      if (!(row >> p[0] >> p[1] >> p[2])) continue;
      cloud.x.push_back(pbf::real(p[0]));
      cloud.y.push_back(pbf::real(p[1]));
      cloud.z.push_back(pbf::real(p[2]));
      cloud.volume.push_back(spacing * spacing * spacing);
      for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], p[a]), hi[a] = std::max(hi[a], p[a]);
    }
  }
  pbf::SurfaceSettings s;
  s.spacing = spacing;
  s.voxel = voxel * spacing;
  s.radius = radius * spacing;
  s.kernel = kernel == "isotropic" ? pbf::SurfaceKernel::isotropic
                                   : (kernel == "spheres" ? pbf::SurfaceKernel::spheres : pbf::SurfaceKernel::anisotropic);
  s.sphere_radius = 0.6 * spacing;
  if (smoothing >= 0) s.smoothing = smoothing;
  // The tank (--domain), else the particles' bounding box grown by half a spacing: its faces are walls.
  for (int a = 0; a < 3; ++a) {
    s.lo[a] = domain.empty() ? lo[a] - spacing / 2 : domain[a];
    s.hi[a] = domain.empty() ? hi[a] + spacing / 2 : domain[3 + a];
  }
  s.wall.fill(true);
  omp_set_num_threads(threads);
  std::vector<double> total, kernels, field, mesh, values;
  pbf::SurfaceMesh result;
  pbf::SurfaceStats stats;
  for (int r = 0; r < repeats; ++r) {
    const double t0 = omp_get_wtime();
    result = pbf::reconstruct_surface(cloud, s, &stats);
    total.push_back(omp_get_wtime() - t0);
    kernels.push_back(stats.seconds_kernels), field.push_back(stats.seconds_field);
    mesh.push_back(stats.seconds_mesh), values.push_back(stats.seconds_attributes);
  }
  const double seconds = median(total);
  std::printf("particles %zu, spacing %g m, voxel %g m (%g spacings), radius %g m (%g spacings), kernel %s, threads %d\n",
              cloud.size(), spacing, s.voxel, voxel, s.radius, radius, kernel.c_str(), threads);
  std::printf("blocks %zu (%zu voxels), mirror images %zu\n", stats.blocks, stats.voxels, stats.images);
  std::printf("vertices %zu, triangles %zu\n", result.mesh.vertices.size(), result.mesh.triangles.size());
  std::printf("seconds (median of %d): kernels %.3f, field %.3f, mesh %.3f, total %.3f\n", repeats, median(kernels),
              median(field), median(mesh), seconds);
  std::printf("particles per core-second: %.0f\n", double(cloud.size()) / (seconds * threads));
  std::printf("memory: reconstruction %.0f MiB, process peak %.0f MiB\n", double(stats.bytes) / (1 << 20), peak_rss_mib());
  std::printf("hash %016llx\n", static_cast<unsigned long long>(mesh_hash(result)));
  if (!ply.empty()) pbf::write_surface_ply(ply, result);
  return 0;
}
