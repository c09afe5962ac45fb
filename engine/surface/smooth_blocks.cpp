// The steps of the field after its blocks are computed (engine/surface/voxel_blocks.cpp): the
// layers beyond the walls, and the smoothing passes.
#include <algorithm>

#include "engine/surface/surface_parts.hpp"

namespace pbf {

namespace {
constexpr int B = VoxelBlocks::kBlock;
}  // namespace

void close_walls(VoxelBlocks& f, const SurfaceSettings& s, bool as_mirror) {
  if (s.walls == SurfaceWalls::none) return;
  const float iso = static_cast<float>(s.iso);
#pragma omp parallel for schedule(dynamic, 1)
  for (std::size_t sl = 0; sl < f.slots(); ++sl) {
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
          out[(k * B + j) * B + i] = as_mirror ? inner : (inner > iso ? 2 * iso - inner : 0.0f);
        }
  }
}

void smooth_blocks(VoxelBlocks& f, const SurfaceSettings& s) {
  std::vector<float> smoothed(f.values.size());
  for (int pass = 0; pass < s.smoothing; ++pass) {
    close_walls(f, s, true);
#pragma omp parallel
    {
      constexpr int P = VoxelBlocks::kPadded;
      std::vector<float> pad(static_cast<std::size_t>(P) * P * P), tmp(pad.size());
#pragma omp for schedule(dynamic, 1)
      for (std::size_t sl = 0; sl < f.slots(); ++sl) {
        f.padded(f.slot_block[0][sl], f.slot_block[1][sl], f.slot_block[2][sl], pad.data());
        const int step[3] = {1, P, P * P};
        float* from = pad.data();
        float* to = tmp.data();
        for (int a = 0; a < 3; ++a) {  // along x, y, z in turn, over the whole padded box
          for (int v = step[a]; v < P * P * P - step[a]; ++v)
            to[v] = 0.25f * from[v - step[a]] + 0.5f * from[v] + 0.25f * from[v + step[a]];
          std::swap(from, to);
        }
        float* out = smoothed.data() + sl * VoxelBlocks::kBlockVoxels;
        for (int k = 0; k < B; ++k)
          for (int j = 0; j < B; ++j)
            for (int i = 0; i < B; ++i) out[(k * B + j) * B + i] = from[((k + 1) * P + (j + 1)) * P + (i + 1)];
      }
    }
    f.values.swap(smoothed);
  }
}

}  // namespace pbf
