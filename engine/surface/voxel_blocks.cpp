// phi on blocks of voxels: each particle is binned to the blocks its kernel's bounding box
// reaches (grown by one voxel downwards, so that every cube the surface crosses has its lower
// corner in a computed block), then each block adds up its particles, in their order, row by
// row over the span of the row inside the ellipsoid (a quadratic in x). At closed or open walls
// the first layer of voxels beyond a face gets 2 iso - phi of its mirror voxel inside (where
// that is inside the surface; 0 elsewhere, as every layer further out), so that the surface
// crosses halfway between them: on the face.
#include <algorithm>
#include <chrono>
#include <cmath>

#include <fmt/format.h>

#include "engine/core/error.hpp"
#include "engine/surface/surface_parts.hpp"

namespace pbf {

namespace {

constexpr int B = VoxelBlocks::kBlock;

long floor_div(long a, long b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

// The voxels whose centres lie in [c - e, c + e] along an axis: [first, last].
void voxel_span(const VoxelBlocks& f, int axis, double c, double e, long& first, long& last) {
  first = static_cast<long>(std::ceil((c - e - f.lo[axis]) / f.v[axis] - 0.5));
  last = static_cast<long>(std::floor((c + e - f.lo[axis]) / f.v[axis] - 0.5));
}

std::string mib(double bytes) { return fmt::format("{:.0f} MiB", bytes / (1 << 20)); }

}  // namespace

float VoxelBlocks::at(long i, long j, long k) const {
  const std::int32_t s = slot(floor_div(i, B), floor_div(j, B), floor_div(k, B));
  if (s < 0) return 0;
  const long li = i - floor_div(i, B) * B, lj = j - floor_div(j, B) * B, lk = k - floor_div(k, B) * B;
  return values[static_cast<std::size_t>(s) * kBlockVoxels + static_cast<std::size_t>((lk * B + lj) * B + li)];
}

void VoxelBlocks::padded(long bx, long by, long bz, float* out) const {
  constexpr int P = kPadded;
  for (int k = 0; k < P; ++k)
    for (int j = 0; j < P; ++j) {
      const long gj = by * B + j - 1, gk = bz * B + k - 1;
      const long cj = floor_div(gj, B), ck = floor_div(gk, B);
      const long lj = gj - cj * B, lk = gk - ck * B;
      float* row = out + (k * P + j) * P;
      // The row crosses three blocks along x: the halo voxel below, the block, two above.
      for (int part = 0; part < 3; ++part) {
        const long cx = bx + part - 1;
        const int from = part == 0 ? 0 : (part == 1 ? 1 : B + 1), to = part == 0 ? 1 : (part == 1 ? B + 1 : P);
        const std::int32_t s = slot(cx, cj, ck);
        if (s < 0) {
          std::fill(row + from, row + to, 0.0f);
          continue;
        }
        const float* src = values.data() + static_cast<std::size_t>(s) * kBlockVoxels + (lk * B + lj) * B;
        const long first = part == 0 ? B - 1 : 0;
        std::copy(src + first, src + first + (to - from), row + from);
      }
    }
}

VoxelBlocks voxel_blocks(const SurfaceParticles& p, const std::vector<ParticleKernel>& kernels,
                         const SurfaceSettings& s, SurfaceStats& stats) {
  const auto start = std::chrono::steady_clock::now();
  VoxelBlocks f;
  for (int a = 0; a < 3; ++a) {
    const double L = s.hi[a] - s.lo[a];
    f.n[a] = std::max(1L, std::lround(L / s.voxel));
    f.lo[a] = s.lo[a];
    f.v[a] = L / static_cast<double>(f.n[a]);
  }
  const std::size_t np = p.size();
  // Each particle's voxel box (grown by one below) and the box of blocks around all of them.
  std::vector<long> box(6 * np);
  long blo[3] = {LONG_MAX, LONG_MAX, LONG_MAX}, bhi[3] = {LONG_MIN, LONG_MIN, LONG_MIN};
  const std::vector<real>* pos[3] = {&p.x, &p.y, &p.z};
  for (std::size_t i = 0; i < np; ++i)
    for (int a = 0; a < 3; ++a) {
      long first, last;
      voxel_span(f, a, (*pos[a])[i], kernels[i].extent[a], first, last);
      box[6 * i + 2 * a] = first - 1;
      box[6 * i + 2 * a + 1] = last;
      blo[a] = std::min(blo[a], floor_div(first - 1, B));
      bhi[a] = std::max(bhi[a], floor_div(last, B));
    }
  if (np == 0) return f;
  double dense = 1;
  for (int a = 0; a < 3; ++a) {
    f.block_lo[a] = blo[a];
    f.block_dims[a] = bhi[a] - blo[a] + 1;
    dense *= static_cast<double>(f.block_dims[a]);
  }
  if (dense * sizeof(std::int32_t) > s.memory_limit)
    throw Error(fmt::format("the surface's grid would need {} for its index of {:.3g} blocks of {}^3 voxels, more "
                            "than the memory limit of {}: raise 'memory' or the voxel size",
                            mib(dense * sizeof(std::int32_t)), dense, B, mib(s.memory_limit)));
  const std::size_t blocks = static_cast<std::size_t>(dense);
  auto block_index = [&](long bx, long by, long bz) {
    return static_cast<std::size_t>(((bz - blo[2]) * f.block_dims[1] + (by - blo[1])) * f.block_dims[0] + (bx - blo[0]));
  };
  // Count the particles of each block, then list them (in particle order) by a prefix sum.
  std::vector<std::uint32_t> start_of(blocks + 1, 0);
  auto each_block = [&](std::size_t i, auto&& visit) {
    const long* b = &box[6 * i];
    for (long bz = floor_div(b[4], B); bz <= floor_div(b[5], B); ++bz)
      for (long by = floor_div(b[2], B); by <= floor_div(b[3], B); ++by)
        for (long bx = floor_div(b[0], B); bx <= floor_div(b[1], B); ++bx) visit(block_index(bx, by, bz));
  };
  for (std::size_t i = 0; i < np; ++i) each_block(i, [&](std::size_t b) { ++start_of[b + 1]; });
  f.block_slot.assign(blocks, -1);
  std::size_t used = 0;
  for (std::size_t b = 0; b < blocks; ++b)
    if (start_of[b + 1] > 0) f.block_slot[b] = static_cast<std::int32_t>(used++);
  const double grid_bytes = static_cast<double>(used) * VoxelBlocks::kBlockVoxels * sizeof(float);
  if (grid_bytes > s.memory_limit)
    throw Error(fmt::format("the surface's grid would need {} ({} blocks of {}^3 voxels of {:.3g} m), more than the "
                            "memory limit of {}: raise 'memory' or the voxel size",
                            mib(grid_bytes), used, B, s.voxel, mib(s.memory_limit)));
  for (std::size_t b = 0; b < blocks; ++b) start_of[b + 1] += start_of[b];
  std::vector<std::uint32_t> members(start_of[blocks]);
  {
    std::vector<std::uint32_t> fill(start_of.begin(), start_of.end() - 1);
    for (std::size_t i = 0; i < np; ++i)
      each_block(i, [&](std::size_t b) { members[fill[b]++] = static_cast<std::uint32_t>(i); });
  }
  std::vector<std::size_t> slot_index(used);  // slot -> block of the box
  for (int a = 0; a < 3; ++a) f.slot_block[a].resize(used);
  for (std::size_t b = 0; b < blocks; ++b)
    if (f.block_slot[b] >= 0) {
      const std::size_t sl = static_cast<std::size_t>(f.block_slot[b]);
      slot_index[sl] = b;
      const long bx = static_cast<long>(b % static_cast<std::size_t>(f.block_dims[0]));
      const long by = static_cast<long>((b / static_cast<std::size_t>(f.block_dims[0])) % static_cast<std::size_t>(f.block_dims[1]));
      const long bz = static_cast<long>(b / static_cast<std::size_t>(f.block_dims[0] * f.block_dims[1]));
      f.slot_block[0][sl] = bx + blo[0], f.slot_block[1][sl] = by + blo[1], f.slot_block[2][sl] = bz + blo[2];
    }
  f.values.assign(used * VoxelBlocks::kBlockVoxels, 0.0f);
  stats.blocks = used;
  stats.voxels = used * VoxelBlocks::kBlockVoxels;
  stats.bytes = std::max(stats.bytes, static_cast<std::size_t>(grid_bytes) + members.size() * 4 + box.size() * 8 +
                                          blocks * 8 + np * sizeof(ParticleKernel));

  // Each block: its particles' kernels, row by row. The density sums V A P(q) straight into the
  // block; the smoothed spheres sum P(q), P(q) d and P(q) r_j (d = x_j - voxel) and then make
  // phi = iso - (|sum P d| - sum P r) / (s sum P): the signed distance to the sphere of radius
  // r-bar about the weighted centre, in spacings, below iso outside it.
  const bool spheres = s.kernel == SurfaceKernel::spheres;
#pragma omp parallel
  {
    std::vector<float> sums(spheres ? 5 * VoxelBlocks::kBlockVoxels : 0);
#pragma omp for schedule(dynamic, 1)
    for (std::size_t sl = 0; sl < used; ++sl) {
      const long bc[3] = {f.slot_block[0][sl], f.slot_block[1][sl], f.slot_block[2][sl]};
      float* out = f.values.data() + sl * VoxelBlocks::kBlockVoxels;
      std::fill(sums.begin(), sums.end(), 0.0f);
      const std::size_t b = slot_index[sl];
      for (std::uint32_t m = start_of[b]; m < start_of[b + 1]; ++m) {
        const std::uint32_t i = members[m];
        const ParticleKernel& k = kernels[i];
        const long* bx = &box[6 * i];
        long lo3[3], hi3[3];
        for (int a = 0; a < 3; ++a) {
          lo3[a] = std::max(bx[2 * a], bc[a] * B);
          hi3[a] = std::min(bx[2 * a + 1], bc[a] * B + B - 1);
        }
        const double cx = p.x[i], cy = p.y[i], cz = p.z[i];
        const double qxx = k.q[0], qyy = k.q[1], qzz = k.q[2], qxy = k.q[3], qxz = k.q[4], qyz = k.q[5];
        for (long kz = lo3[2]; kz <= hi3[2]; ++kz) {
          const double dz = f.centre(2, kz) - cz;
          for (long jy = lo3[1]; jy <= hi3[1]; ++jy) {
            const double dy = f.centre(1, jy) - cy;
            // d.Q.d = qxx dx^2 + b dx + c along the row; its span below 1 in voxels.
            const double bq = 2 * (qxy * dy + qxz * dz), cq = qyy * dy * dy + qzz * dz * dz + 2 * qyz * dy * dz;
            const double disc = bq * bq - 4 * qxx * (cq - 1);
            if (disc <= 0) continue;
            const double root = std::sqrt(disc);
            const double x0 = cx + (-bq - root) / (2 * qxx), x1 = cx + (-bq + root) / (2 * qxx);
            long first, last;
            voxel_span(f, 0, 0.5 * (x0 + x1), 0.5 * (x1 - x0), first, last);
            first = std::max(first, lo3[0]);
            last = std::min(last, hi3[0]);
            if (first > last) continue;
            const std::size_t row = static_cast<std::size_t>(((kz - bc[2] * B) * B + (jy - bc[1] * B)) * B);
            const long x0_block = bc[0] * B;
            const float fq = static_cast<float>(qxx), fb = static_cast<float>(bq), fc = static_cast<float>(cq);
            const float x_first = static_cast<float>(f.centre(0, first) - cx), step = static_cast<float>(f.v[0]);
            const float w = k.weight;
            if (!spheres) {
              float* r = out + row - x0_block;
#pragma omp simd
              for (long ix = first; ix <= last; ++ix) {
                const float dx = x_first + static_cast<float>(ix - first) * step;
                const float t = std::max(0.0f, 1.0f - (fq * dx * dx + fb * dx + fc));
                r[ix] += w * t * t * t;
              }
            } else {
              float* r = sums.data() + row - x0_block;
              const std::size_t n = VoxelBlocks::kBlockVoxels;
              const float fy = static_cast<float>(dy), fz = static_cast<float>(dz);
              const float radius = k.radius;
#pragma omp simd
              for (long ix = first; ix <= last; ++ix) {
                const float dx = x_first + static_cast<float>(ix - first) * step;
                const float t = std::max(0.0f, 1.0f - (fq * dx * dx + fb * dx + fc));
                const float pw = t * t * t;
                r[ix] += pw;
                r[n + ix] -= pw * dx;
                r[2 * n + ix] -= pw * fy;
                r[3 * n + ix] -= pw * fz;
                r[4 * n + ix] += pw * radius;
              }
            }
          }
        }
      }
      if (spheres) {
        const std::size_t n = VoxelBlocks::kBlockVoxels;
        const double iso = s.iso, far = s.radius / s.spacing;
        for (std::size_t v = 0; v < n; ++v) {
          const double W = sums[v];
          if (!(W > 0)) {
            out[v] = static_cast<float>(iso - far);
            continue;
          }
          const double ox = sums[n + v] / W, oy = sums[2 * n + v] / W, oz = sums[3 * n + v] / W;
          const double distance = std::sqrt(ox * ox + oy * oy + oz * oz) - sums[4 * n + v] / W;
          out[v] = static_cast<float>(iso - distance / s.spacing);
        }
      }
    }
  }

  // The voxels beyond the walls.
  if (s.walls != SurfaceWalls::none) {
    const float iso = static_cast<float>(s.iso);
#pragma omp parallel for schedule(dynamic, 1)
    for (std::size_t sl = 0; sl < used; ++sl) {
      const long bc[3] = {f.slot_block[0][sl], f.slot_block[1][sl], f.slot_block[2][sl]};
      bool touches = false;
      for (int a = 0; a < 3; ++a)
        touches |= (s.wall[2 * a] && bc[a] * B < 0) || (s.wall[2 * a + 1] && bc[a] * B + B > f.n[a]);
      if (!touches) continue;
      float* out = f.values.data() + sl * VoxelBlocks::kBlockVoxels;
      for (int k = 0; k < B; ++k)
        for (int j = 0; j < B; ++j)
          for (int i = 0; i < B; ++i) {
            long g[3] = {bc[0] * B + i, bc[1] * B + j, bc[2] * B + k}, mirror[3];
            bool beyond = false, first_layer = true;
            for (int a = 0; a < 3; ++a) {
              mirror[a] = g[a];
              if (s.wall[2 * a] && g[a] < 0) {
                beyond = true, first_layer &= g[a] == -1, mirror[a] = -1 - g[a];
              } else if (s.wall[2 * a + 1] && g[a] >= f.n[a]) {
                beyond = true, first_layer &= g[a] == f.n[a], mirror[a] = 2 * f.n[a] - 1 - g[a];
              }
            }
            if (!beyond) continue;
            const float inner = first_layer ? f.at(mirror[0], mirror[1], mirror[2]) : 0.0f;
            out[(k * B + j) * B + i] = inner > iso ? 2 * iso - inner : 0.0f;
          }
    }
  }
  stats.seconds_field = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return f;
}

}  // namespace pbf
