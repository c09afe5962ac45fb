// surface_openvdb: measures OpenVDB as the alternative to the engine's own surface
// reconstruction (particles -> narrow-band level set -> smoothing -> marching cubes), on one
// particle frame, so the two can be chosen between by measurement.
//
// Phases, each timed by wall clock (std::chrono::steady_clock; process CPU time beside it),
// median of --repeats (default 3) full runs, each from an empty grid:
//   rasterize  openvdb::tools::ParticlesToLevelSet::rasterizeSpheres(particles, R): the CSG
//              union of spheres of radius R, narrow band of 3 voxels each side; finalize(prune)
//   smooth     N iterations of openvdb::tools::LevelSetFilter (default: meanCurvature, one
//              step of mean-curvature flow each, then the filter's re-normalisation)
//   mesh       openvdb::tools::volumeToMesh(grid, points, triangles, quads, 0, 0):
//              isovalue 0, adaptivity 0 (all quads; each counts as two triangles)
// Threads are limited with tbb::global_control(max_allowed_parallelism, T). Printed:
// particles, voxel size, active voxels, vertices, triangles, each phase's time, total,
// particles per core-second (particles / (total s x T)), peak RSS (VmHWM), and a 64-bit
// FNV-1a hash of the mesh (points then quads then triangles, as produced), to compare runs
// at 1 and 2 threads for bit-identity. Then, untimed, on the last repeat's mesh: connected
// components, area, whether isolated particles and small droplets (clusters of touching spheres)
// still have a surface around them, and with --probe a patch's bumpiness (spread of face
// normals, area over projected area, vertex heights).
//
// Frame: text, one particle per line "x y z" in metres; lines starting with '#' ignored.
//
//   cmake -S . -B /tmp/vdb-build -DCMAKE_BUILD_TYPE=Release -DPBF_BUILD_TESTS=OFF
//   cmake --build build --target surface_openvdb (the main build has it: build/bench/surface_openvdb)
//   /tmp/vdb-build/bench/surface_openvdb FILE --spacing S [--voxel V (S/2)] [--radius R (S)]
//       [--smooth N (2)] [--filter meancurvature|gaussian|laplacian] [--threads T (all)]
//       [--repeats K (3)] [--obj OUT.obj] [--probe x0 x1 y0 y1 z0 z1]
#include <openvdb/openvdb.h>
#include <openvdb/tools/LevelSetFilter.h>
#include <openvdb/tools/LevelSetUtil.h>
#include <openvdb/tools/ParticlesToLevelSet.h>
#include <openvdb/tools/VolumeToMesh.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <iterator>
#include <numeric>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace {

using openvdb::Real;
using openvdb::Vec3R;

// The particle list adapter ParticlesToLevelSet (and its PointPartitioner) need.
struct ParticleList {
  using PosType = Vec3R;
  std::vector<Vec3R> pos;
  Real radius = 0;
  size_t size() const { return pos.size(); }
  void getPos(size_t n, Vec3R& xyz) const { xyz = pos[n]; }
  void getPosRad(size_t n, Vec3R& xyz, Real& r) const { xyz = pos[n]; r = radius; }
};

[[noreturn]] void usage(const char* why) {
  std::fprintf(stderr,
               "surface_openvdb: %s\nusage: surface_openvdb FILE --spacing S [--voxel V] [--radius R] "
               "[--smooth N] [--filter meancurvature|gaussian|laplacian] [--threads T] [--repeats K] "
               "[--obj OUT.obj] [--probe x0 x1 y0 y1 z0 z1]\n",
               why);
  std::exit(2);
}

std::vector<Vec3R> read_frame(const std::string& path, bool& saw_end) {
  std::ifstream in(path, std::ios::binary);
  if (!in) usage(("cannot open " + path).c_str());
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::vector<Vec3R> pts;
  saw_end = false;
  const char* p = text.c_str();
  const char* end = p + text.size();
  size_t line = 0;
  while (p < end) {
    const char* eol = static_cast<const char*>(std::memchr(p, '\n', size_t(end - p)));
    if (!eol) eol = end;
    ++line;
    const char* q = p;
    while (q < eol && (*q == ' ' || *q == '\t' || *q == '\r')) ++q;
    if (q < eol && *q == '#') {
      if (std::strncmp(q, "# end", 5) == 0) saw_end = true;
    } else if (q < eol) {
      std::string s(q, eol);  // strtod must not run past the line
      char* e = nullptr;
      double v[3];
      const char* c = s.c_str();
      for (double& x : v) {
        x = std::strtod(c, &e);
        if (e == c) {
          std::fprintf(stderr, "surface_openvdb: %s:%zu: not \"x y z\"\n", path.c_str(), line);
          std::exit(1);
        }
        c = e;
      }
      pts.emplace_back(v[0], v[1], v[2]);
    }
    p = eol + 1;
  }
  return pts;
}

double now_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
double cpu_s() {
  timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

double vmhwm_mib() {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("VmHWM:", 0) == 0) return std::strtod(line.c_str() + 6, nullptr) / 1024.0;  // kB
  return -1;
}

struct Fnv {
  uint64_t h = 1469598103934665603ull;
  void add(const void* data, size_t n) {
    const auto* b = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 1099511628211ull;
  }
};

struct Mesh {
  std::vector<openvdb::Vec3s> points;
  std::vector<openvdb::Vec3I> triangles;
  std::vector<openvdb::Vec4I> quads;
  size_t triangle_count() const { return triangles.size() + 2 * quads.size(); }
  uint64_t hash() const {
    Fnv f;
    f.add(points.data(), points.size() * sizeof(points[0]));
    f.add(quads.data(), quads.size() * sizeof(quads[0]));
    f.add(triangles.data(), triangles.size() * sizeof(triangles[0]));
    return f.h;
  }
  template <class F>
  void for_each_triangle(F&& f) const {  // quads split along their 0-2 diagonal
    for (const auto& t : triangles) f(t[0], t[1], t[2]);
    for (const auto& q : quads) {
      f(q[0], q[1], q[2]);
      f(q[0], q[2], q[3]);
    }
  }
};

uint64_t grid_hash(const openvdb::FloatGrid& g) {  // active values with their coordinates
  Fnv f;
  for (auto it = g.cbeginValueOn(); it; ++it) {
    const openvdb::Coord c = it.getCoord();
    const float v = *it;
    f.add(c.data(), sizeof(int32_t) * 3);
    f.add(&v, sizeof v);
  }
  return f.h;
}

// Cells of a uniform grid over points, for neighbour queries: (cell key, index) sorted.
struct CellIndex {
  double h;
  std::vector<std::pair<uint64_t, uint32_t>> cells;
  static uint64_t key(int64_t i, int64_t j, int64_t k) {
    const int64_t o = int64_t(1) << 20;
    return (uint64_t(i + o) << 42) | (uint64_t(j + o) << 21) | uint64_t(k + o);
  }
  template <class V>
  CellIndex(const std::vector<V>& p, double cell) : h(cell) {
    cells.reserve(p.size());
    for (size_t n = 0; n < p.size(); ++n)
      cells.emplace_back(key(int64_t(std::floor(p[n][0] / h)), int64_t(std::floor(p[n][1] / h)),
                             int64_t(std::floor(p[n][2] / h))),
                         uint32_t(n));
    std::sort(cells.begin(), cells.end());
  }
  template <class F>
  void near(const Vec3R& x, F&& f) const {  // f(index) for the 27 cells around x
    const int64_t i = int64_t(std::floor(x[0] / h)), j = int64_t(std::floor(x[1] / h)),
                  k = int64_t(std::floor(x[2] / h));
    for (int64_t a = -1; a <= 1; ++a)
      for (int64_t b = -1; b <= 1; ++b)
        for (int64_t c = -1; c <= 1; ++c) {
          const uint64_t kk = key(i + a, j + b, k + c);
          auto lo = std::lower_bound(cells.begin(), cells.end(), std::make_pair(kk, uint32_t(0)));
          for (; lo != cells.end() && lo->first == kk; ++lo) f(lo->second);
        }
  }
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) usage("no frame file");
  std::string file, obj, filter = "meancurvature";
  double spacing = 0, voxel = 0, radius = 0;
  int smooth = 2, repeats = 3;
  int threads = int(std::max(1u, std::thread::hardware_concurrency()));
  bool probe = false;
  double box[6] = {0, 0, 0, 0, 0, 0};
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto val = [&]() -> const char* {
      if (i + 1 >= argc) usage((a + " needs a value").c_str());
      return argv[++i];
    };
    if (a == "--spacing") spacing = std::atof(val());
    else if (a == "--voxel") voxel = std::atof(val());
    else if (a == "--radius") radius = std::atof(val());
    else if (a == "--smooth") smooth = std::atoi(val());
    else if (a == "--filter") filter = val();
    else if (a == "--threads") threads = std::atoi(val());
    else if (a == "--repeats") repeats = std::atoi(val());
    else if (a == "--obj") obj = val();
    else if (a == "--probe") {
      for (double& b : box) b = std::atof(val());
      probe = true;
    } else if (a.rfind("--", 0) == 0) usage(("unknown option " + a).c_str());
    else if (file.empty()) file = a;
    else usage("more than one frame file");
  }
  if (file.empty()) usage("no frame file");
  if (!(spacing > 0)) usage("--spacing S (> 0) is required");
  if (voxel <= 0) voxel = spacing / 2;
  if (radius <= 0) radius = spacing;
  if (threads < 1 || repeats < 1 || smooth < 0) usage("bad --threads, --repeats or --smooth");
  if (filter != "meancurvature" && filter != "gaussian" && filter != "laplacian")
    usage("--filter is meancurvature, gaussian or laplacian");

  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
  openvdb::initialize();

  ParticleList particles;
  bool saw_end = false;
  const double t_read = now_s();
  particles.pos = read_frame(file, saw_end);
  particles.radius = radius;
  std::printf("frame        %s (%s\"# end\" line), read in %.2f s\n", file.c_str(), saw_end ? "" : "NO ",
              now_s() - t_read);
  const size_t np = particles.size();
  std::printf("particles    %zu\nspacing      %g m   voxel %g m   radius %g m (%.2f voxels)   band 3 voxels\n",
              np, spacing, voxel, radius, radius / voxel);
  std::printf("smoothing    %d x LevelSetFilter::%s%s\nthreads      %d   repeats %d\n", smooth,
              filter.c_str(), filter == "gaussian" ? "(width 1)" : "", threads, repeats);
  if (np == 0) return 1;

  std::vector<double> w_r, w_s, w_m, w_t, c_r, c_s, c_m;
  std::vector<uint64_t> hashes;
  Mesh mesh;
  openvdb::FloatGrid::Ptr grid;
  size_t active_raster = 0, active_smooth = 0, ignored = 0;
  uint64_t ghash_raster = 0;
  for (int rep = 0; rep < repeats; ++rep) {
    mesh = Mesh();
    grid.reset();
    const double w0 = now_s(), c0 = cpu_s();
    grid = openvdb::createLevelSet<openvdb::FloatGrid>(voxel, 3.0);
    {
      openvdb::tools::ParticlesToLevelSet<openvdb::FloatGrid> raster(*grid);
      raster.rasterizeSpheres(particles, radius);
      raster.finalize(/*prune=*/true);
      ignored = raster.getMinCount() + raster.getMaxCount();
    }
    const double w1 = now_s(), c1 = cpu_s();
    if (rep == repeats - 1) {
      active_raster = grid->activeVoxelCount();
      ghash_raster = grid_hash(*grid);
    }
    const double w1b = now_s(), c1b = cpu_s();
    if (smooth > 0) {
      openvdb::tools::LevelSetFilter<openvdb::FloatGrid> f(*grid);
      for (int k = 0; k < smooth; ++k) {
        if (filter == "meancurvature") f.meanCurvature();
        else if (filter == "gaussian") f.gaussian(1);
        else f.laplacian();
      }
    }
    const double w2 = now_s(), c2 = cpu_s();
    openvdb::tools::volumeToMesh(*grid, mesh.points, mesh.triangles, mesh.quads, /*isovalue=*/0.0,
                                 /*adaptivity=*/0.0);
    const double w3 = now_s(), c3 = cpu_s();
    w_r.push_back(w1 - w0), w_s.push_back(w2 - w1b), w_m.push_back(w3 - w2);
    w_t.push_back((w1 - w0) + (w2 - w1b) + (w3 - w2));
    c_r.push_back(c1 - c0), c_s.push_back(c2 - c1b), c_m.push_back(c3 - c2);
    hashes.push_back(mesh.hash());
    std::printf("repeat %d     rasterize %.3f s  smooth %.3f s  mesh %.3f s  total %.3f s  hash %016llx\n", rep,
                w1 - w0, w2 - w1b, w3 - w2, w_t.back(), (unsigned long long)hashes.back());
  }
  active_smooth = grid->activeVoxelCount();
  const uint64_t ghash_smooth = grid_hash(*grid);
  const double total = median(w_t);
  bool stable = true;
  for (uint64_t h : hashes) stable = stable && h == hashes[0];

  std::printf("ignored      %zu particles (radius outside OpenVDB's 1.5..100 voxels)\n", ignored);
  std::printf("active       %zu voxels after rasterize, %zu after smoothing\n", active_raster, active_smooth);
  std::printf("mesh         %zu vertices, %zu triangles (%zu quads + %zu triangles)\n", mesh.points.size(),
              mesh.triangle_count(), mesh.quads.size(), mesh.triangles.size());
  std::printf("time median  rasterize %.3f s  smooth %.3f s  mesh %.3f s  total %.3f s (wall)\n",
              median(w_r), median(w_s), median(w_m), total);
  std::printf("cpu median   rasterize %.3f s  smooth %.3f s  mesh %.3f s (process CPU time)\n", median(c_r),
              median(c_s), median(c_m));
  std::printf("rate         %.0f particles per core-second (%zu / (%.3f s x %d))\n",
              double(np) / (total * threads), np, total, threads);
  std::printf("peak RSS     %.1f MiB (VmHWM)\n", vmhwm_mib());
  std::printf("grid hash    rasterized %016llx  smoothed %016llx\n", (unsigned long long)ghash_raster,
              (unsigned long long)ghash_smooth);
  std::printf("mesh hash    %016llx (FNV-1a 64; %s across the %d repeats)\n", (unsigned long long)hashes.back(),
              stable ? "same" : "DIFFERENT", repeats);

  // --- Untimed analysis of the last mesh ---
  const auto& P = mesh.points;
  // Connected components (union-find over polygon vertices).
  std::vector<uint32_t> parent(P.size());
  std::iota(parent.begin(), parent.end(), 0u);
  auto find = [&](uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  auto unite = [&](uint32_t a, uint32_t b) {
    a = find(a), b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  };
  mesh.for_each_triangle([&](uint32_t a, uint32_t b, uint32_t c) { unite(a, b), unite(a, c); });
  std::vector<uint32_t> comp_size(P.size(), 0);
  std::vector<std::array<float, 6>> comp_box(P.size(), {1e30f, -1e30f, 1e30f, -1e30f, 1e30f, -1e30f});
  for (uint32_t v = 0; v < P.size(); ++v) {
    const uint32_t r = find(v);
    ++comp_size[r];
    for (int d = 0; d < 3; ++d)
      comp_box[r][2 * d] = std::min(comp_box[r][2 * d], P[v][d]),
                    comp_box[r][2 * d + 1] = std::max(comp_box[r][2 * d + 1], P[v][d]);
  }
  size_t ncomp = 0, nsmall = 0;
  for (uint32_t v = 0; v < P.size(); ++v)
    if (comp_size[v]) {
      ++ncomp;
      const auto& b = comp_box[v];
      const double diag = std::sqrt(double(b[1] - b[0]) * (b[1] - b[0]) + double(b[3] - b[2]) * (b[3] - b[2]) +
                                    double(b[5] - b[4]) * (b[5] - b[4]));
      if (diag < 4 * radius) ++nsmall;
    }
  // Enclosed volume per piece (divergence theorem; volumeToMesh winds inward, hence the minus):
  // a negative one is a cavity, a bubble of gas the union of spheres leaves inside the liquid.
  std::vector<double> comp_vol(P.size(), 0.0);
  mesh.for_each_triangle([&](uint32_t a, uint32_t b, uint32_t c) {
    comp_vol[find(a)] -= Vec3R(P[a]).dot(Vec3R(P[b]).cross(Vec3R(P[c]))) / 6.0;
  });
  size_t ncav = 0;
  for (uint32_t v = 0; v < P.size(); ++v) ncav += comp_size[v] && comp_vol[v] < 0;
  std::printf("components   %zu connected pieces, %zu of them droplet-sized (bounding-box diagonal < 4R), "
              "%zu cavities (negative volume)\n",
              ncomp, nsmall, ncav);
  double total_area = 0;
  mesh.for_each_triangle([&](uint32_t a, uint32_t b, uint32_t c) {
    total_area += 0.5 * (Vec3R(P[b]) - Vec3R(P[a])).cross(Vec3R(P[c]) - Vec3R(P[a])).length();
  });
  std::printf("area         %.6f m^2 of mesh\n", total_area);

  // Droplets: clusters of particles whose spheres touch (centres closer than 2R), of 1 particle
  // (isolated) and of 2..9; one survives if the mesh has a vertex within R of one of its
  // particles (marching-cubes vertices of a sphere lie at or just inside R, and any other
  // cluster's surface is farther than R away).
  {
    const CellIndex pidx(particles.pos, 2 * radius);
    std::vector<uint32_t> up(np);
    std::iota(up.begin(), up.end(), 0u);
    auto pfind = [&](uint32_t x) {
      while (up[x] != x) x = up[x] = up[up[x]];
      return x;
    };
    for (size_t n = 0; n < np; ++n) {
      const Vec3R x = particles.pos[n];
      pidx.near(x, [&](uint32_t m) {
        if (m > n && (particles.pos[m] - x).lengthSqr() < 4 * radius * radius) {
          const uint32_t a = pfind(uint32_t(n)), b = pfind(m);
          if (a != b) up[std::max(a, b)] = std::min(a, b);
        }
      });
    }
    std::vector<uint32_t> csize(np, 0);
    for (size_t n = 0; n < np; ++n) ++csize[pfind(uint32_t(n))];
    std::vector<char> alive(np, 0);
    const CellIndex vidx(P, radius);
    for (size_t n = 0; n < np; ++n) {
      const uint32_t r = pfind(uint32_t(n));
      if (csize[r] >= 10 || alive[r]) continue;
      const Vec3R x = particles.pos[n];
      vidx.near(x, [&](uint32_t v) {
        const Vec3R d(P[v][0] - x[0], P[v][1] - x[1], P[v][2] - x[2]);
        if (d.lengthSqr() <= radius * radius * (1 + 1e-6)) alive[r] = 1;
      });
    }
    size_t iso = 0, iso_alive = 0, small = 0, small_alive = 0;
    for (size_t r = 0; r < np; ++r) {
      if (csize[r] == 1) ++iso, iso_alive += alive[r];
      else if (csize[r] > 1 && csize[r] < 10) ++small, small_alive += alive[r];
    }
    std::printf("isolated     %zu particles with no other within 2R; %zu still have surface within R\n", iso,
                iso_alive);
    std::printf("droplets     %zu clusters of 2..9 touching spheres; %zu still have surface within R\n", small,
                small_alive);
  }

  // Bumpiness of a patch: triangles whose centroid lies in the probe box.
  if (probe) {
    double area = 0;
    Vec3R vec_area(0, 0, 0);
    std::vector<std::pair<Vec3R, double>> normals;
    std::vector<uint32_t> verts;
    mesh.for_each_triangle([&](uint32_t a, uint32_t b, uint32_t c) {
      const Vec3R A(P[a]), B(P[b]), C(P[c]);
      const Vec3R g = (A + B + C) / 3.0;
      if (g[0] < box[0] || g[0] > box[1] || g[1] < box[2] || g[1] > box[3] || g[2] < box[4] || g[2] > box[5])
        return;
      const Vec3R n2 = (B - A).cross(C - A);  // twice the vector area
      const double ar = 0.5 * n2.length();
      if (ar <= 0) return;
      area += ar;
      vec_area += 0.5 * n2;
      normals.emplace_back(n2 / (2 * ar), ar);
      verts.push_back(a), verts.push_back(b), verts.push_back(c);
    });
    if (area > 0) {
      const double proj = vec_area.length();
      const Vec3R nbar = vec_area / proj;
      double s2 = 0, worst = 0;
      for (const auto& [n, ar] : normals) {
        const double ang = std::acos(std::clamp(n.dot(nbar), -1.0, 1.0)) * 180.0 / M_PI;
        s2 += ar * ang * ang;
        worst = std::max(worst, ang);
      }
      std::sort(verts.begin(), verts.end());
      verts.erase(std::unique(verts.begin(), verts.end()), verts.end());
      double hmean = 0, hmin = 1e30, hmax = -1e30, h2 = 0;
      for (uint32_t v : verts) {
        const double h = Vec3R(P[v]).dot(nbar);
        hmean += h, hmin = std::min(hmin, h), hmax = std::max(hmax, h);
      }
      hmean /= double(verts.size());
      for (uint32_t v : verts) h2 += std::pow(Vec3R(P[v]).dot(nbar) - hmean, 2);
      std::printf("probe        %zu triangles, mean normal (%.3f %.3f %.3f) (as wound: points inward)\n",
                  normals.size(), nbar[0], nbar[1], nbar[2]);
      std::printf("probe        area / projected area %.4f; face-normal angle from mean: rms %.2f deg, max %.1f deg\n",
                  area / proj, std::sqrt(s2 / area), worst);
      std::printf("probe        vertex height along mean normal: rms %.3f voxels, range %.3f voxels\n",
                  std::sqrt(h2 / double(verts.size())) / voxel, (hmax - hmin) / voxel);
    } else {
      std::printf("probe        no triangles in the box\n");
    }
  }

  if (!obj.empty()) {
    std::FILE* out = std::fopen(obj.c_str(), "w");
    if (!out) usage(("cannot write " + obj).c_str());
    // volumeToMesh winds its polygons clockwise seen from outside (right-hand normals point
    // into the liquid); OBJ readers expect counter-clockwise, so the order is reversed here.
    std::fprintf(out, "# surface_openvdb: %zu vertices, %zu quads, %zu triangles\n", P.size(), mesh.quads.size(),
                 mesh.triangles.size());
    for (const auto& p : P) std::fprintf(out, "v %.9g %.9g %.9g\n", p[0], p[1], p[2]);
    for (const auto& q : mesh.quads) std::fprintf(out, "f %u %u %u %u\n", q[3] + 1, q[2] + 1, q[1] + 1, q[0] + 1);
    for (const auto& t : mesh.triangles) std::fprintf(out, "f %u %u %u\n", t[2] + 1, t[1] + 1, t[0] + 1);
    std::fclose(out);
    std::printf("obj          %s\n", obj.c_str());
  }
  return 0;
}
