// phi on blocks of voxels: each particle is binned to the blocks its kernel's bounding box
// reaches (grown by one voxel downwards, so that every cube the surface crosses has its lower
// corner in a computed block); the band of blocks that kernels of particles without a full
// neighbourhood reach is computed (then, in rounds, any full block the surface turns out to
// reach), each block adding up its particles, in their order, row by row over the span of the
// row inside the ellipsoid (a quadratic in x). At closed or open walls the first layer of voxels
// beyond a face gets 2 iso - phi of its mirror voxel inside (where that is inside the surface; 0
// elsewhere, as every layer further out), so that the surface crosses halfway between them: on
// the face. Last, the smoothing passes, and the droplets added after them. Meshed in parts,
// a part holds its own blocks and a ring of one block around them along its axis, finds the
// full blocks at the surface among its own, and agrees with the others on all of them each
// round.
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
  if (s < 0) return s == kFull ? inside : 0.0f;
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
          std::fill(row + from, row + to, s == kFull ? inside : 0.0f);
          continue;
        }
        const float* src = values.data() + static_cast<std::size_t>(s) * kBlockVoxels + (lk * B + lj) * B;
        const long first = part == 0 ? B - 1 : 0;
        std::copy(src + first, src + first + (to - from), row + from);
      }
    }
}

VoxelBlocks voxel_blocks(const SurfaceParticles& p, const std::vector<ParticleKernel>& kernels,
                         const SurfaceSettings& s, const SurfacePart& part, SurfaceStats& stats) {
  const auto start = std::chrono::steady_clock::now();
  VoxelBlocks f;
  // Inside the fluid phi is about 1, or, for the smoothed spheres, iso + r / s.
  f.inside = static_cast<float>(s.kernel == SurfaceKernel::spheres ? s.iso + s.sphere_radius / s.spacing : 1.0);
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
  // Meshed in parts, every part takes part in each agreement, with values or without: on the
  // box (the union of the parts': the blocks a neighbour holds lie in it), on the statuses of
  // the blocks in each part's ring (its neighbours', who see all the particles that decide
  // them), then once a round on the full blocks found at the surface.
  auto agree = [&](std::vector<std::int64_t>& values, std::string& error) {
    if (part.agree) part.agree(values, error);
    if (!error.empty()) throw Error(error);
  };
  // An error is agreed too (in the next agreement, where the others learn of it), then thrown.
  auto refuse = [&](std::string message) {
    std::vector<std::int64_t> none;
    agree(none, message);
    throw Error(message);
  };
  if (part.agree) {
    std::vector<std::int64_t> extent = {blo[0], bhi[0], blo[1], bhi[1], blo[2], bhi[2]};
    std::string error;
    agree(extent, error);
    for (std::size_t k = 0; k < extent.size(); k += 6)
      for (int a = 0; a < 3; ++a) {
        blo[a] = std::min(blo[a], static_cast<long>(extent[k + 2 * a]));
        bhi[a] = std::max(bhi[a], static_cast<long>(extent[k + 2 * a + 1]));
      }
  }
  // The part's blocks and their ring along its axis.
  const int axis = part.axis;
  blo[axis] = std::max(blo[axis], part.first - 1);
  bhi[axis] = std::min(bhi[axis], part.end);
  auto owned = [&](const long c[3]) { return c[axis] >= part.first && c[axis] < part.end; };
  if (np == 0 || blo[0] > bhi[0] || blo[1] > bhi[1] || blo[2] > bhi[2]) {  // no blocks: the others' agreements
    std::vector<std::int64_t> statuses;
    std::string error;
    agree(statuses, error);
    for (;;) {
      std::vector<std::int64_t> none;
      agree(none, error);
      if (none.empty()) return f;
    }
  }
  double dense = 1;
  for (int a = 0; a < 3; ++a) {
    f.block_lo[a] = blo[a];
    f.block_dims[a] = bhi[a] - blo[a] + 1;
    dense *= static_cast<double>(f.block_dims[a]);
  }
  if (dense * sizeof(std::int32_t) > s.memory_limit)
    refuse(fmt::format("the surface's grid would need {} for its index of {:.3g} blocks of {}^3 voxels, more "
                       "than the memory limit of {}: raise 'memory' or the voxel size",
                       mib(dense * sizeof(std::int32_t)), dense, B, mib(s.memory_limit)));
  const std::size_t blocks = static_cast<std::size_t>(dense);
  auto block_index = [&](long bx, long by, long bz) {
    return static_cast<std::size_t>(((bz - blo[2]) * f.block_dims[1] + (by - blo[1])) * f.block_dims[0] + (bx - blo[0]));
  };
  // Block b's coordinate along axis a.
  auto coordinate = [&](std::size_t b, int a) {
    const std::size_t nx = static_cast<std::size_t>(f.block_dims[0]), ny = static_cast<std::size_t>(f.block_dims[1]);
    const std::size_t along = a == 0 ? b % nx : (a == 1 ? (b / nx) % ny : b / (nx * ny));
    return static_cast<long>(along) + blo[a];
  };
  // The band: the blocks that a kernel of a particle without a full neighbourhood reaches
  // (grown by two voxels), where the surface can be. The other blocks some kernel reaches lie
  // inside the fluid (phi well above iso: kFull, not computed); the rest are empty (phi = 0).
  auto each_block = [&](std::size_t i, long grow, auto&& visit) {
    const long* b = &box[6 * i];
    for (long bz = floor_div(b[4] - grow, B); bz <= floor_div(b[5] + grow, B); ++bz)
      for (long by = floor_div(b[2] - grow, B); by <= floor_div(b[3] + grow, B); ++by)
        for (long bx = floor_div(b[0] - grow, B); bx <= floor_div(b[1] + grow, B); ++bx) {
          if (bx < blo[0] || by < blo[1] || bz < blo[2] || bx >= blo[0] + f.block_dims[0] ||
              by >= blo[1] + f.block_dims[1] || bz >= blo[2] + f.block_dims[2])
            continue;
          visit(block_index(bx, by, bz));
        }
  };
  // The particles' lists of blocks, counted before anything is made of them: a kernel far wider
  // than a block (an absurd radius or a tiny voxel) makes many.
  double pairs = 0;
  for (std::size_t i = 0; i < np; ++i) {
    double spanned = 1;
    for (int a = 0; a < 3; ++a)
      spanned *= static_cast<double>(floor_div(box[6 * i + 2 * a + 1] + 2, B) - floor_div(box[6 * i + 2 * a] - 2, B) + 1);
    pairs += spanned;
  }
  if (pairs * sizeof(std::uint32_t) > s.memory_limit)
    refuse(fmt::format("the surface's grid would need {} to list the particles of its blocks ({:.3g} entries), "
                       "more than the memory limit of {}: raise 'memory' or the voxel size, or lower the radius",
                       mib(pairs * sizeof(std::uint32_t)), pairs, mib(s.memory_limit)));
  f.block_slot.assign(blocks, VoxelBlocks::kEmpty);
  for (std::size_t i = 0; i < np; ++i)
    each_block(i, 0, [&](std::size_t b) { f.block_slot[b] = VoxelBlocks::kFull; });
  for (std::size_t i = 0; i < np; ++i)
    if (!kernels[i].interior) each_block(i, 2, [&](std::size_t b) { f.block_slot[b] = 0; });
  if (part.agree) {  // the ring's statuses are its owners': (x, y, z, 0 band or 1 full) each
    std::vector<std::int64_t> statuses;
    for (std::size_t b = 0; b < blocks; ++b) {
      const long c[3] = {coordinate(b, 0), coordinate(b, 1), coordinate(b, 2)};
      if (f.block_slot[b] == VoxelBlocks::kEmpty || !owned(c) || (c[axis] != part.first && c[axis] != part.end - 1)) continue;
      statuses.insert(statuses.end(), {c[0], c[1], c[2], f.block_slot[b] == 0 ? 0 : 1});
    }
    std::string error;
    agree(statuses, error);
    for (std::size_t b = 0; b < blocks; ++b) {
      const long c[3] = {coordinate(b, 0), coordinate(b, 1), coordinate(b, 2)};
      if (!owned(c)) f.block_slot[b] = VoxelBlocks::kEmpty;
    }
    for (std::size_t k = 0; k < statuses.size(); k += 4) {
      const long c[3] = {static_cast<long>(statuses[k]), static_cast<long>(statuses[k + 1]), static_cast<long>(statuses[k + 2])};
      if (owned(c) || c[axis] < blo[axis] || c[axis] > bhi[axis]) continue;
      f.block_slot[block_index(c[0], c[1], c[2])] = statuses[k + 3] == 0 ? 0 : VoxelBlocks::kFull;
    }
  }
  // A block with voxels beyond a closed wall is computed too, for the layer that closes the
  // surface on the wall (below), and so is one with the last layer before an upper wall, which
  // holds the edges that cross it; one wholly beyond a wall sums no particles.
  auto beyond_wall = [&](std::size_t b, bool wholly) {
    const long c[3] = {coordinate(b, 0), coordinate(b, 1), coordinate(b, 2)};
    if (s.walls == SurfaceWalls::none) return false;
    for (int a = 0; a < 3; ++a) {
      const long first = c[a] * B, last = first + B - 1;
      if (s.wall[2 * a] && (wholly ? last < 0 : first < 0)) return true;
      if (s.wall[2 * a + 1] && (wholly ? first >= f.n[a] : last >= f.n[a] - 1)) return true;
    }
    return false;
  };
  std::size_t used = 0;
  for (std::size_t b = 0; b < blocks; ++b)
    if (f.block_slot[b] == 0 || (f.block_slot[b] == VoxelBlocks::kFull && beyond_wall(b, false)))
      f.block_slot[b] = static_cast<std::int32_t>(used++);
  const double grid_bytes = static_cast<double>(used) * VoxelBlocks::kBlockVoxels * sizeof(float);
  if (grid_bytes > s.memory_limit)
    refuse(fmt::format("the surface's grid would need {} ({} blocks of {}^3 voxels of {:.3g} m), more than the "
                       "memory limit of {}: raise 'memory' or the voxel size",
                       mib(grid_bytes), used, B, s.voxel, mib(s.memory_limit)));
  // Each block's particles (a band block's, and a full one's, which may need computing after
  // all), listed in particle order: counted, a prefix sum, then filled.
  std::vector<std::uint32_t> start_of(blocks + 1, 0);
  std::vector<char> sums(blocks, 0);
  for (std::size_t b = 0; b < blocks; ++b) sums[b] = f.block_slot[b] != VoxelBlocks::kEmpty && !beyond_wall(b, true);
  for (std::size_t i = 0; i < np; ++i)
    each_block(i, 0, [&](std::size_t b) { start_of[b + 1] += sums[b]; });
  for (std::size_t b = 0; b < blocks; ++b) start_of[b + 1] += start_of[b];
  std::vector<std::uint32_t> members(start_of[blocks]);
  {
    std::vector<std::uint32_t> fill(start_of.begin(), start_of.end() - 1);
    for (std::size_t i = 0; i < np; ++i)
      each_block(i, 0, [&](std::size_t b) {
        if (sums[b]) members[fill[b]++] = static_cast<std::uint32_t>(i);
      });
  }
  std::vector<std::size_t> slot_index;  // slot -> block of the box
  auto add_slot = [&](std::size_t b) {
    slot_index.push_back(b);
    for (int a = 0; a < 3; ++a) f.slot_block[a].push_back(coordinate(b, a));
  };
  for (std::size_t b = 0; b < blocks; ++b)
    if (f.block_slot[b] >= 0) add_slot(b);
  f.values.assign(used * VoxelBlocks::kBlockVoxels, 0.0f);
  // Each block: its particles' kernels, row by row. The density sums V A P(q) straight into the
  // block; the smoothed spheres sum P(q), P(q) d and P(q) r_j (d = x_j - voxel) and then make
  // phi = iso - (|sum P d| - sum P r) / (s sum P): the signed distance to the sphere of radius
  // r-bar about the weighted centre, in spacings, below iso outside it.
  const bool spheres = s.kernel == SurfaceKernel::spheres;
  // Under smoothing, the droplets (the isolated particles' kernels) are added after it, so that
  // it rounds the bulk's surface without wiping out what a splash threw off: `droplets`
  // selects which particles a call adds (all, when that split does not apply).
  const bool split = s.smoothing > 0 && !spheres;
  auto compute = [&](std::size_t first_slot, std::size_t end_slot, bool droplets) {
#pragma omp parallel
  {
    std::vector<float> sums(spheres ? 5 * VoxelBlocks::kBlockVoxels : 0);
#pragma omp for schedule(dynamic, 1)
    for (std::size_t sl = first_slot; sl < end_slot; ++sl) {
      const long bc[3] = {f.slot_block[0][sl], f.slot_block[1][sl], f.slot_block[2][sl]};
      float* out = f.values.data() + sl * VoxelBlocks::kBlockVoxels;
      std::fill(sums.begin(), sums.end(), 0.0f);
      const std::size_t b = slot_index[sl];
      for (std::uint32_t m = start_of[b]; m < start_of[b + 1]; ++m) {
        const std::uint32_t i = members[m];
        const ParticleKernel& k = kernels[i];
        if (split && k.isolated != droplets) continue;
        const long* bx = &box[6 * i];
        long lo3[3], hi3[3];
        for (int a = 0; a < 3; ++a) {
          lo3[a] = std::max(bx[2 * a], bc[a] * B);
          hi3[a] = std::min(bx[2 * a + 1], bc[a] * B + B - 1);
        }
        const double cx = p.x[i], cy = p.y[i], cz = p.z[i];
        const double qxx = k.q[0], qyy = k.q[1], qzz = k.q[2], qxy = k.q[3], qxz = k.q[4], qyz = k.q[5];
        const double half_over_qxx = 0.5 / qxx, voxels_per_m = 1 / f.v[0];
        const double row_start = (cx - f.lo[0]) * voxels_per_m - 0.5;  // the centre, in voxel indices
        for (long kz = lo3[2]; kz <= hi3[2]; ++kz) {
          const double dz = f.centre(2, kz) - cz;
          for (long jy = lo3[1]; jy <= hi3[1]; ++jy) {
            const double dy = f.centre(1, jy) - cy;
            // d.Q.d = qxx dx^2 + b dx + c along the row; its span below 1 in voxels.
            const double bq = 2 * (qxy * dy + qxz * dz), cq = qyy * dy * dy + qzz * dz * dz + 2 * qyz * dy * dz;
            const double disc = bq * bq - 4 * qxx * (cq - 1);
            if (disc <= 0) continue;
            // The roots dx = (-b -/+ sqrt(disc)) / (2 qxx), as voxel indices.
            const double root = std::sqrt(disc) * half_over_qxx, middle = -bq * half_over_qxx;
            long first = static_cast<long>(std::ceil(row_start + (middle - root) * voxels_per_m));
            long last = static_cast<long>(std::floor(row_start + (middle + root) * voxels_per_m));
            first = std::max(first, lo3[0]);
            last = std::min(last, hi3[0]);
            if (first > last) continue;
            const std::size_t row = static_cast<std::size_t>(((kz - bc[2] * B) * B + (jy - bc[1] * B)) * B);
            const long x0_block = bc[0] * B;
            const float fq = static_cast<float>(qxx), fb = static_cast<float>(bq), fc = static_cast<float>(cq);
            const float x_first = static_cast<float>(f.centre(0, first) - cx), step = static_cast<float>(f.v[0]);
            const float w = k.weight;
            const int count = static_cast<int>(last - first + 1);
            if (!spheres) {
              float* r = out + row + (first - x0_block);
#pragma omp simd
              for (int i = 0; i < count; ++i) {
                const float dx = x_first + static_cast<float>(i) * step;
                const float q = 1.0f - (fq * dx * dx + fb * dx + fc);
                const float t = q > 0.0f ? q : 0.0f;
                r[i] += w * t * t * t;
              }
            } else {
              float* r = sums.data() + row + (first - x0_block);
              const std::size_t n = VoxelBlocks::kBlockVoxels;
              const float fy = static_cast<float>(dy), fz = static_cast<float>(dz);
              const float radius = k.radius;
#pragma omp simd
              for (int i = 0; i < count; ++i) {
                const float dx = x_first + static_cast<float>(i) * step;
                const float q = 1.0f - (fq * dx * dx + fb * dx + fc);
                const float t = q > 0.0f ? q : 0.0f;
                const float pw = t * t * t;
                r[i] += pw;
                r[n + i] -= pw * dx;
                r[2 * n + i] -= pw * fy;
                r[3 * n + i] -= pw * fz;
                r[4 * n + i] += pw * radius;
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
  };


  // A full block next to a computed one whose facing layer is not inside the surface may hold
  // the surface after all (the band is a rule of thumb, not a bound): it is computed too, in
  // rounds until no such block is left.
  auto full_blocks_at_the_surface = [&] {
    std::vector<std::size_t> found;
    const float iso = static_cast<float>(s.iso);
    for (std::size_t b = 0; b < blocks; ++b) {
      if (f.block_slot[b] != VoxelBlocks::kFull) continue;
      const long c[3] = {coordinate(b, 0), coordinate(b, 1), coordinate(b, 2)};
      if (!owned(c)) continue;  // the ring's are its owner's to find
      bool at_surface = false;
      for (int a = 0; a < 3 && !at_surface; ++a)
        for (int side = -1; side <= 1 && !at_surface; side += 2) {
          long nc[3] = {c[0], c[1], c[2]};
          nc[a] += side;
          const std::int32_t sl = f.slot(nc[0], nc[1], nc[2]);
          // (Across a wall the closing layer faces it, and the edges that cross belong to
          // the block beyond a lower wall, or to the computed block before an upper one.)
          if (sl < 0 || beyond_wall(slot_index[static_cast<std::size_t>(sl)], true)) continue;
          // The neighbour's layer that faces this block: index (side < 0 ? B - 1 : 0) along a.
          const float* v = f.values.data() + static_cast<std::size_t>(sl) * VoxelBlocks::kBlockVoxels;
          const int layer = side < 0 ? B - 1 : 0, stride[3] = {1, B, B * B};
          const int u = (a + 1) % 3, w = (a + 2) % 3;
          for (int p = 0; p < B && !at_surface; ++p)
            for (int q = 0; q < B; ++q)
              if (!(v[layer * stride[a] + p * stride[u] + q * stride[w]] > iso)) {
                at_surface = true;
                break;
              }
        }
      if (at_surface) found.push_back(b);
    }
    return found;
  };
  compute(0, f.slots(), false);
  for (;;) {
    close_walls(f, s, false);
    std::vector<std::int64_t> more;  // the blocks found, three coordinates each
    for (std::size_t b : full_blocks_at_the_surface())
      for (int a = 0; a < 3; ++a) more.push_back(coordinate(b, a));
    std::string error;
    agree(more, error);
    if (more.empty()) break;
    const std::size_t first = f.slots();
    for (std::size_t m = 0; m < more.size(); m += 3) {
      const long c[3] = {static_cast<long>(more[m]), static_cast<long>(more[m + 1]), static_cast<long>(more[m + 2])};
      if (c[axis] < blo[axis] || c[axis] > bhi[axis]) continue;  // neither this part's nor its ring's
      const std::size_t b = block_index(c[0], c[1], c[2]);
      if (f.block_slot[b] != VoxelBlocks::kFull) continue;
      f.block_slot[b] = static_cast<std::int32_t>(f.slots());
      add_slot(b);
    }
    const double bytes = static_cast<double>(f.slots()) * VoxelBlocks::kBlockVoxels * sizeof(float);
    if (bytes > s.memory_limit)
      refuse(fmt::format("the surface's grid would need {} ({} blocks of {}^3 voxels of {:.3g} m), more than the "
                         "memory limit of {}: raise 'memory' or the voxel size",
                         mib(bytes), f.slots(), B, s.voxel, mib(s.memory_limit)));
    f.values.resize(f.slots() * VoxelBlocks::kBlockVoxels, 0.0f);
    compute(first, f.slots(), false);
  }
  if (s.smoothing > 0) {
    smooth_blocks(f, s);
    if (split) compute(0, f.slots(), true);
    close_walls(f, s, false);
  }
  stats.blocks = f.slots();
  stats.voxels = f.slots() * VoxelBlocks::kBlockVoxels;
  stats.bytes = std::max(stats.bytes, f.values.size() * sizeof(float) + members.size() * 4 + box.size() * 8 +
                                          blocks * 8 + np * sizeof(ParticleKernel));
  stats.seconds_field = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return f;
}

}  // namespace pbf
