// The steps of the field after its blocks are computed (engine/surface/voxel_blocks.cpp): the
// layers beyond the walls, and the smoothing passes.
#include <algorithm>
#include <cstdint>

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
    // Along each axis, each of the block's 16 layers: inside (0), the first layer beyond a
    // wall (1) or one further out (2), and its mirror layer inside.
    std::uint8_t state[3][B];
    long mirror[3][B];
    for (int a = 0; a < 3; ++a)
      for (int l = 0; l < B; ++l) {
        const long g = bc[a] * B + l;
        state[a][l] = 0, mirror[a][l] = g;
        if (s.wall[2 * a] && g < 0) state[a][l] = g == -1 ? 1 : 2, mirror[a][l] = -1 - g;
        else if (s.wall[2 * a + 1] && g >= f.n[a]) state[a][l] = g == f.n[a] ? 1 : 2, mirror[a][l] = 2 * f.n[a] - 1 - g;
        // What the smoothing reads beyond a periodic face is the fluid there: the far side's.
        if (as_mirror && s.periodic[a] && state[a][l] == 1) mirror[a][l] = g < 0 ? f.n[a] - 1 : 0;
      }
    for (int k = 0; k < B; ++k)
      for (int j = 0; j < B; ++j) {
        const int row = std::max(state[2][k], state[1][j]);
        float* r = out + (k * B + j) * B;
        for (int i = 0; i < B; ++i) {
          const int where = std::max(row, static_cast<int>(state[0][i]));
          if (where == 0) continue;
          // Only the first layer beyond (along every axis it is beyond) reads its mirror.
          const float inner = where == 1 ? f.at(mirror[0][i], mirror[1][j], mirror[2][k]) : 0.0f;
          r[i] = as_mirror ? inner : (inner > iso ? 2 * iso - inner : 0.0f);
        }
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
