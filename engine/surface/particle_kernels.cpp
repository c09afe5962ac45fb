// Mirror images at the walls and each particle's smoothing kernel (the equations are in
// engine/surface/surface.hpp): isotropic, or Yu & Turk's ellipsoid from the weighted
// covariance of the neighbours within R, found by a Jacobi eigen-decomposition.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "engine/core/parallel.hpp"
#include "engine/surface/surface_parts.hpp"

namespace pbf {

SurfaceParticles with_images(const SurfaceCloud& cloud, const SurfaceSettings& s) {
  SurfaceParticles p;
  const std::size_t n = cloud.size();
  p.x = cloud.x, p.y = cloud.y, p.z = cloud.z;
  p.source.resize(n);
  for (std::size_t i = 0; i < n; ++i) p.source[i] = static_cast<std::uint32_t>(i);
  p.flips.assign(n, 0);
  p.originals = n;
  if (s.walls == SurfaceWalls::none) return p;
  const std::vector<real>* pos[3] = {&cloud.x, &cloud.y, &cloud.z};
  std::vector<real>* out[3] = {&p.x, &p.y, &p.z};
  for (std::size_t i = 0; i < n; ++i) {
    // Along each axis: the face within R to mirror across (-1 lower, +1 upper, 0 none).
    int near[3] = {0, 0, 0};
    for (int a = 0; a < 3; ++a) {
      const double c = (*pos[a])[i];
      const double to_lo = c - s.lo[a], to_hi = s.hi[a] - c;
      if (s.wall[2 * a] && to_lo < s.radius && to_lo <= to_hi) near[a] = -1;
      else if (s.wall[2 * a + 1] && to_hi < s.radius) near[a] = 1;
    }
    // One image per non-empty set of those faces (at a corner, the images of images too).
    for (int set = 1; set < 8; ++set) {
      bool ok = true;
      for (int a = 0; a < 3; ++a)
        if (((set >> a) & 1) && near[a] == 0) ok = false;
      if (!ok) continue;
      for (int a = 0; a < 3; ++a) {
        const double c = (*pos[a])[i];
        const double face = near[a] < 0 ? s.lo[a] : s.hi[a];
        out[a]->push_back(((set >> a) & 1) ? static_cast<real>(2 * face - c) : static_cast<real>(c));
      }
      p.source.push_back(static_cast<std::uint32_t>(i));
      p.flips.push_back(static_cast<std::uint8_t>(set));
    }
  }
  return p;
}

namespace {

// Eigen-decomposition of a symmetric 3 x 3 matrix by cyclic Jacobi rotations: the eigenvalues
// in `value`, eigenvector k in column k of `vec`.
void symmetric_eigen(double m[3][3], double value[3], double vec[3][3]) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) vec[i][j] = i == j;
  for (int sweep = 0; sweep < 16; ++sweep) {
    const double off = m[0][1] * m[0][1] + m[0][2] * m[0][2] + m[1][2] * m[1][2];
    const double diag = m[0][0] * m[0][0] + m[1][1] * m[1][1] + m[2][2] * m[2][2];
    if (off <= 1e-30 * diag || off == 0) break;
    for (int p = 0; p < 2; ++p)
      for (int q = p + 1; q < 3; ++q) {
        if (m[p][q] == 0) continue;
        const double theta = (m[q][q] - m[p][p]) / (2 * m[p][q]);
        const double t = (theta >= 0 ? 1 : -1) / (std::fabs(theta) + std::sqrt(theta * theta + 1));
        const double c = 1 / std::sqrt(t * t + 1), s = t * c;
        for (int k = 0; k < 3; ++k) {  // m = J^T m J, columns then rows
          const double mkp = m[k][p], mkq = m[k][q];
          m[k][p] = c * mkp - s * mkq;
          m[k][q] = s * mkp + c * mkq;
        }
        for (int k = 0; k < 3; ++k) {
          const double mpk = m[p][k], mqk = m[q][k];
          m[p][k] = c * mpk - s * mqk;
          m[q][k] = s * mpk + c * mqk;
        }
        for (int k = 0; k < 3; ++k) {
          const double vkp = vec[k][p], vkq = vec[k][q];
          vec[k][p] = c * vkp - s * vkq;
          vec[k][q] = s * vkp + c * vkq;
        }
      }
  }
  for (int k = 0; k < 3; ++k) value[k] = m[k][k];
}

constexpr double kPoly6 = 315.0 / (64.0 * std::numbers::pi);

// The kernel with semi-axes a[k] along the unit vectors e[.][k] (columns), weighing volume V.
ParticleKernel ellipsoid(const double a[3], const double e[3][3], double volume) {
  ParticleKernel k{};
  double q[3][3] = {};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int c = 0; c < 3; ++c) q[i][j] += e[i][c] * e[j][c] / (a[c] * a[c]);
  k.q[0] = static_cast<float>(q[0][0]), k.q[1] = static_cast<float>(q[1][1]), k.q[2] = static_cast<float>(q[2][2]);
  k.q[3] = static_cast<float>(q[0][1]), k.q[4] = static_cast<float>(q[0][2]), k.q[5] = static_cast<float>(q[1][2]);
  k.weight = static_cast<float>(volume * kPoly6 / (a[0] * a[1] * a[2]));
  for (int i = 0; i < 3; ++i) {
    double w2 = 0;
    for (int c = 0; c < 3; ++c) w2 += e[i][c] * a[c] * e[i][c] * a[c];
    k.extent[i] = static_cast<float>(std::sqrt(w2));
  }
  return k;
}

}  // namespace

std::vector<ParticleKernel> particle_kernels(const SurfaceParticles& p, const SurfaceCloud& cloud,
                                             const SurfaceSettings& s, NeighborGrid& cells) {
  const std::size_t n = p.size(), originals = p.originals;
  Domain box;
  for (int a = 0; a < 3; ++a) box.lo[a] = s.lo[a], box.hi[a] = s.hi[a];
  cells.bin(p.x.data(), p.y.data(), p.z.data(), n, box, s.radius);
  std::vector<ParticleKernel> kernels(n);
  const double R = s.radius, R2 = R * R;
  const double identity[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};

  const GridGeometry& g = cells.geometry();
  const std::uint32_t* starts = cells.cell_starts();
  const std::uint32_t* order = cells.sorted_order().data();
  const long* dims = g.dims;

  for_blocks(originals, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const double V = cloud.volume[i];
      if (s.kernel != SurfaceKernel::anisotropic) {
        const double a[3] = {R, R, R};
        kernels[i] = ellipsoid(a, identity, V);
        kernels[i].radius = static_cast<float>(s.sphere_radius * std::cbrt(V) / s.spacing);
        continue;
      }
      const double xi = p.x[i], yi = p.y[i], zi = p.z[i];
      long c[3];
      const double at[3] = {xi, yi, zi};
      for (int a = 0; a < 3; ++a) c[a] = g.cell_along(a, at[a]);
      // Weighted sums over the neighbours within R (the particle itself included), offsets
      // from the particle: sum w, sum w d, sum w d d^T.
      double W = 0, m[3] = {0, 0, 0}, mm[6] = {0, 0, 0, 0, 0, 0};
      int neighbours = -1;  // not counting itself
      for (long cz = std::max(0L, c[2] - 1); cz <= std::min(dims[2] - 1, c[2] + 1); ++cz)
        for (long cy = std::max(0L, c[1] - 1); cy <= std::min(dims[1] - 1, c[1] + 1); ++cy)
          for (long cx = std::max(0L, c[0] - 1); cx <= std::min(dims[0] - 1, c[0] + 1); ++cx) {
            const std::size_t cell = static_cast<std::size_t>((cz * dims[1] + cy) * dims[0] + cx);
            for (std::uint32_t k = starts[cell]; k < starts[cell + 1]; ++k) {
              const std::uint32_t j = order[k];
              const double dx = p.x[j] - xi, dy = p.y[j] - yi, dz = p.z[j] - zi;
              const double r2 = dx * dx + dy * dy + dz * dz;
              if (r2 >= R2) continue;
              const double r = std::sqrt(r2) / R, w = 1 - r * r * r;
              ++neighbours;
              W += w;
              m[0] += w * dx, m[1] += w * dy, m[2] += w * dz;
              mm[0] += w * dx * dx, mm[1] += w * dy * dy, mm[2] += w * dz * dz;
              mm[3] += w * dx * dy, mm[4] += w * dx * dz, mm[5] += w * dy * dz;
            }
          }
      if (neighbours < s.isolated_below) {
        const double a[3] = {R / 2, R / 2, R / 2};
        kernels[i] = ellipsoid(a, identity, V);
        continue;
      }
      for (double& v : m) v /= W;
      double C[3][3] = {{mm[0] / W - m[0] * m[0], mm[3] / W - m[0] * m[1], mm[4] / W - m[0] * m[2]},
                        {0, mm[1] / W - m[1] * m[1], mm[5] / W - m[1] * m[2]},
                        {0, 0, mm[2] / W - m[2] * m[2]}};
      C[1][0] = C[0][1], C[2][0] = C[0][2], C[2][1] = C[1][2];
      double value[3], vec[3][3];
      symmetric_eigen(C, value, vec);
      const double largest = std::max({value[0], value[1], value[2]});
      double a[3];
      for (int k = 0; k < 3; ++k)
        a[k] = largest > 0 ? R * std::max(std::sqrt(std::max(0.0, value[k]) / largest), 1 / s.max_stretch) : R;
      kernels[i] = ellipsoid(a, vec, V);
    }
  });

  // Images: the original's kernel, reflected (Q's off-diagonal terms that pair a reflected
  // axis with one that is not change sign).
  for (std::size_t i = originals; i < n; ++i) {
    ParticleKernel k = kernels[p.source[i]];
    const int f = p.flips[i];
    auto flipped = [&](int a) { return (f >> a) & 1; };
    if (flipped(0) != flipped(1)) k.q[3] = -k.q[3];
    if (flipped(0) != flipped(2)) k.q[4] = -k.q[4];
    if (flipped(1) != flipped(2)) k.q[5] = -k.q[5];
    kernels[i] = k;
  }
  return kernels;
}

}  // namespace pbf
