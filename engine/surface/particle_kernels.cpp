// Mirror images at the walls and each particle's smoothing kernel (the equations are in
// engine/surface/surface.hpp): isotropic, or Yu & Turk's ellipsoid from the weighted
// covariance of the neighbours within R, decomposed as a body's inertia is (principal_axes).
#include <algorithm>
#include <cmath>
#include <numbers>
#include <type_traits>

#include "engine/bodies/mass_properties.hpp"
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
  const std::vector<real>* pos[3] = {&cloud.x, &cloud.y, &cloud.z};
  std::vector<real>* out[3] = {&p.x, &p.y, &p.z};
  for (std::size_t i = 0; i < n && s.walls != SurfaceWalls::none; ++i) {
    // Along each axis: the face within R to mirror (or wrap) across (-1 lower, +1 upper, 0 none).
    int near[3] = {0, 0, 0};
    for (int a = 0; a < 3; ++a) {
      const double c = (*pos[a])[i];
      const double to_lo = c - s.lo[a], to_hi = s.hi[a] - c;
      if (s.wall[2 * a] && to_lo < s.radius && to_lo <= to_hi) near[a] = -1;
      else if (s.wall[2 * a + 1] && to_hi < s.radius) near[a] = 1;
    }
    // One image per non-empty set of those faces (at a corner, the images of images too):
    // mirrored across a wall, translated across a periodic face (the fluid beyond it).
    for (int set = 1; set < 8; ++set) {
      bool ok = true;
      for (int a = 0; a < 3; ++a)
        if (((set >> a) & 1) && near[a] == 0) ok = false;
      if (!ok) continue;
      int flips = 0;
      for (int a = 0; a < 3; ++a) {
        const double c = (*pos[a])[i];
        const double face = near[a] < 0 ? s.lo[a] : s.hi[a];
        double image = c;
        if ((set >> a) & 1) {
          if (s.periodic[a]) {
            image = c - near[a] * (s.hi[a] - s.lo[a]);
          } else {
            image = 2 * face - c;
            flips |= 1 << a;
          }
        }
        out[a]->push_back(static_cast<real>(image));
      }
      p.source.push_back(static_cast<std::uint32_t>(i));
      p.flips.push_back(static_cast<std::uint8_t>(flips));
    }
  }
  // Across a solid's face: x - 2 d n (a vector attribute keeps its value: near a wall the
  // fluid moves along it).
  p.solid_images = p.size();
  for (const auto& m : cloud.mirrors) {
    const std::size_t i = m.particle;
    out[0]->push_back(static_cast<real>(cloud.x[i] - 2 * m.distance * m.normal[0]));
    out[1]->push_back(static_cast<real>(cloud.y[i] - 2 * m.distance * m.normal[1]));
    out[2]->push_back(static_cast<real>(cloud.z[i] - 2 * m.distance * m.normal[2]));
    p.source.push_back(static_cast<std::uint32_t>(i));
    p.flips.push_back(0);
    p.solid_normals.push_back(m.normal);
  }
  return p;
}

namespace {

constexpr double kPoly6 = 315.0 / (64.0 * std::numbers::pi);
constexpr int kLanes = 4;  // one SSE vector per sum: the eleven sums stay in registers

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

// The kernel k mirrored across a plane of unit normal n.
ParticleKernel reflected(ParticleKernel k, const std::array<double, 3>& n) {
  const double q[3][3] = {{k.q[0], k.q[3], k.q[4]}, {k.q[3], k.q[1], k.q[5]}, {k.q[4], k.q[5], k.q[2]}};
  double h[3][3], inverse[3][3];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) h[r][c] = (r == c ? 1.0 : 0.0) - 2 * n[r] * n[c];
  // Q^-1 by cofactors (Q is positive definite: an ellipsoid's).
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      inverse[c][r] = q[(r + 1) % 3][(c + 1) % 3] * q[(r + 2) % 3][(c + 2) % 3] -
                      q[(r + 1) % 3][(c + 2) % 3] * q[(r + 2) % 3][(c + 1) % 3];
  const double det = q[0][0] * inverse[0][0] + q[0][1] * inverse[1][0] + q[0][2] * inverse[2][0];
  auto sandwich = [&](const double m[3][3], int r, int c) {  // (H M H)_rc
    double sum = 0;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) sum += h[r][a] * m[a][b] * h[b][c];
    return sum;
  };
  const int row[6] = {0, 1, 2, 0, 0, 1}, col[6] = {0, 1, 2, 1, 2, 2};
  ParticleKernel out = k;
  for (int e = 0; e < 6; ++e) out.q[e] = static_cast<float>(sandwich(q, row[e], col[e]));
  for (int a = 0; a < 3; ++a) out.extent[a] = static_cast<float>(std::sqrt(std::max(0.0, sandwich(inverse, a, a) / det)));
  return out;
}

}  // namespace

std::vector<ParticleKernel> particle_kernels(const SurfaceParticles& p, const SurfaceCloud& cloud,
                                             const SurfaceSettings& s, NeighborGrid& cells) {
  const std::size_t n = p.size(), originals = p.originals;
  Domain box;
  for (int a = 0; a < 3; ++a) box.lo[a] = s.lo[a], box.hi[a] = s.hi[a];
  cells.bin(p.x.data(), p.y.data(), p.z.data(), n, box, s.radius);
  std::vector<ParticleKernel> kernels(n);
  const double R = s.radius;
  const double identity[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};

  const GridGeometry& g = cells.geometry();
  const std::uint32_t* starts = cells.cell_starts();
  const std::uint32_t* order = cells.sorted_order().data();
  const long* dims = g.dims;
  // Positions packed in cell order, so that a cell's candidates are read in vectors, and
  // padded with kLanes far-away points for the last vector (1e15 m: its square stays finite).
  std::vector<float> px(n + kLanes, 1e15f), py(n + kLanes, 1e15f), pz(n + kLanes, 1e15f);
  for (std::size_t k = 0; k < n; ++k) px[k] = p.x[order[k]], py[k] = p.y[order[k]], pz[k] = p.z[order[k]];
  // The weight sum of a full neighbourhood: sum over a lattice of (1 - r^2/R^2)^3, about its
  // integral 4 pi (16/315) (R/s)^3.
  const double full = 4 * std::numbers::pi * 16.0 / 315.0 * std::pow(R / s.spacing, 3);

  // The sums over the neighbours within R of a particle at (xi, yi, zi) in cell c: count,
  // sum w, sum w d and, with `moments` (std::true_type), sum w d d^T, in kLanes lanes (a vector each; the
  // sums stay in registers), added up in a fixed order at the end.
  const float inv_R2 = static_cast<float>(1 / (R * R));
  auto neighbour_sums = [&](auto moments, float xi, float yi, float zi, const long c[3], double sum[11]) {
    alignas(32) float n_[kLanes] = {}, w_[kLanes] = {}, x_[kLanes] = {}, y_[kLanes] = {}, z_[kLanes] = {},
                      xx_[kLanes] = {}, yy_[kLanes] = {}, zz_[kLanes] = {}, xy_[kLanes] = {}, xz_[kLanes] = {},
                      yz_[kLanes] = {};
    for (long cz = std::max(0L, c[2] - 1); cz <= std::min(dims[2] - 1, c[2] + 1); ++cz)
      for (long cy = std::max(0L, c[1] - 1); cy <= std::min(dims[1] - 1, c[1] + 1); ++cy) {
        const long row = (cz * dims[1] + cy) * dims[0];
        const std::size_t first = starts[row + std::max(0L, c[0] - 1)];
        const std::size_t last = starts[row + std::min(dims[0] - 1, c[0] + 1) + 1];
        for (std::size_t k0 = first; k0 < last; k0 += kLanes) {
          const float *ax = px.data() + k0, *ay = py.data() + k0, *az = pz.data() + k0;
          const int left = static_cast<int>(last - k0);
#pragma omp simd
          for (int l = 0; l < kLanes; ++l) {  // past `last`: the padding, far away
            const float dx = ax[l] - xi, dy = ay[l] - yi, dz = az[l] - zi;
            const float q = 1.0f - (dx * dx + dy * dy + dz * dz) * inv_R2;
            const float inside = static_cast<float>((q > 0.0f) & (l < left));
            const float t = q * inside, w = t * t * t;
            n_[l] += inside;
            w_[l] += w;
            x_[l] += w * dx;
            y_[l] += w * dy;
            z_[l] += w * dz;
            if constexpr (decltype(moments)::value) {
              xx_[l] += w * dx * dx;
              yy_[l] += w * dy * dy;
              zz_[l] += w * dz * dz;
              xy_[l] += w * dx * dy;
              xz_[l] += w * dx * dz;
              yz_[l] += w * dy * dz;
            }
          }
        }
      }
    const float* lanes[11] = {n_, w_, x_, y_, z_, xx_, yy_, zz_, xy_, xz_, yz_};
    for (int v = 0; v < 11; ++v) {
      sum[v] = 0;
      for (int l = 0; l < kLanes; ++l) sum[v] += lanes[v][l];
    }
  };

  for_blocks(originals, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const double V = cloud.volume[i];
      const float xi = static_cast<float>(p.x[i]), yi = static_cast<float>(p.y[i]), zi = static_cast<float>(p.z[i]);
      long c[3];
      const double at[3] = {p.x[i], p.y[i], p.z[i]};
      for (int a = 0; a < 3; ++a) c[a] = g.cell_along(a, at[a]);
      // Weighted sums over the neighbours within R (the particle itself included), offsets
      // from the particle: sum w, sum w d, and (only where the kernel is an ellipsoid: the
      // particle is not inside the fluid) sum w d d^T, with w = (1 - r^2/R^2)^3.
      double sum[11];
      neighbour_sums(std::false_type{}, xi, yi, zi, c, sum);
      const double count = sum[0], W = sum[1];
      // Inside the fluid: a full neighbourhood around the particle (its kernel's support then
      // lies where phi is well above iso: the surface's blocks need not see it alone).
      const double m[3] = {sum[2] / W, sum[3] / W, sum[4] / W};
      const bool interior = W > 0.85 * full && std::sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]) < 0.1 * R;
      if (s.kernel != SurfaceKernel::anisotropic || interior) {
        // (Inside the fluid Yu & Turk's covariance is a sphere's: no decomposition needed.)
        const double a[3] = {R, R, R};
        kernels[i] = ellipsoid(a, identity, V);
        kernels[i].radius = static_cast<float>(s.sphere_radius * std::cbrt(V) / s.spacing);
      } else if (count - 1 < s.isolated_below) {  // not counting itself
        const double a[3] = {R / 2, R / 2, R / 2};
        kernels[i] = ellipsoid(a, identity, V);
        kernels[i].isolated = true;
      } else {
        neighbour_sums(std::true_type{}, xi, yi, zi, c, sum);
        const double xx = sum[5], yy = sum[6], zz = sum[7], xy = sum[8], xz = sum[9], yz = sum[10];
        Matrix3 C{{{xx / W - m[0] * m[0], xy / W - m[0] * m[1], xz / W - m[0] * m[2]},
                   {0, yy / W - m[1] * m[1], yz / W - m[1] * m[2]},
                   {0, 0, zz / W - m[2] * m[2]}}};
        C[1][0] = C[0][1], C[2][0] = C[0][2], C[2][1] = C[1][2];
        std::array<double, 3> value;
        Matrix3 axes;
        principal_axes(C, value, axes);  // the eigenvalues and eigenvectors (columns), by Jacobi rotations
        double vec[3][3];
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c) vec[r][c] = axes[r][c];
        const double largest = std::max({value[0], value[1], value[2]});
        double a[3];
        for (int k = 0; k < 3; ++k)
          a[k] = largest > 0 ? R * std::max(std::sqrt(std::max(0.0, value[k]) / largest), 1 / s.max_stretch) : R;
        kernels[i] = ellipsoid(a, vec, V);
      }
      kernels[i].interior = interior;
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
  // Across a solid's face: Q' = H Q H with H = I - 2 n n^T, and the bounding box's half-widths
  // sqrt((Q'^-1)_aa) (Q'^-1 = H Q^-1 H).
  for (std::size_t i = p.solid_images; i < n; ++i)
    kernels[i] = reflected(kernels[p.source[i]], p.solid_normals[i - p.solid_images]);
  return kernels;
}

}  // namespace pbf
