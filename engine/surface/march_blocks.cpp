// Marching cubes over a part's blocks of voxels. Every edge the surface crosses is one vertex,
// owned by the block that holds the edge's lower voxel. Each block, in parallel, makes its
// vertices (in the order of their edges) and the triangles of the cubes whose lower corner it
// holds, naming a vertex on an edge of a block above by that block and the edge:
// join_surface_pieces (surface_pieces.cpp) numbers them. Cubes follow engine/surface/cube_cases.
#include <algorithm>
#include <chrono>
#include <cmath>

#include <fmt/format.h>

#include "engine/core/error.hpp"
#include "engine/surface/cube_cases.hpp"
#include "engine/surface/surface_parts.hpp"

namespace pbf {

namespace {

constexpr int B = VoxelBlocks::kBlock;
constexpr int P = VoxelBlocks::kPadded;

// A block-local edge: (voxel (k B + j) B + i) * 3 + axis.
using EdgeKey = std::uint16_t;
static_assert(B * B * B * 3 <= 65536);

// The padded array's index of block-local voxel (i, j, k) (the halo starts at -1).
inline int padded_at(int i, int j, int k) { return ((k + 1) * P + (j + 1)) * P + (i + 1); }

}  // namespace

SurfacePiece march_blocks(const VoxelBlocks& f, const SurfaceSettings& s, const SurfacePart& part) {
  const float iso = static_cast<float>(s.iso);
  const int step[3] = {1, P, P * P};
  // The part's blocks, in (z, y, x) order: the order the pieces join in.
  std::vector<std::size_t> order;
  for (std::size_t sl = 0; sl < f.slots(); ++sl) {
    const long along = f.slot_block[part.axis][sl];
    if (along >= part.first && along < part.end) order.push_back(sl);
  }
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    for (int c = 2; c >= 0; --c)
      if (f.slot_block[c][a] != f.slot_block[c][b]) return f.slot_block[c][a] < f.slot_block[c][b];
    return false;
  });
  const std::size_t nb = order.size();
  // Each block's piece, made in parallel, then laid end to end.
  struct BlockPiece {
    std::vector<EdgeKey> keys;
    std::vector<std::array<double, 3>> vertices;
    std::vector<std::array<float, 3>> normals;
    std::vector<std::uint8_t> on_wall;
    std::vector<std::array<std::uint32_t, 3>> corners;
  };
  std::vector<BlockPiece> pieces(nb);
  const CubeCases& cases = cube_cases();
  int corner_offset[8][3];
  for (int c = 0; c < 8; ++c) corner_offset[c][0] = c & 1, corner_offset[c][1] = (c >> 1) & 1, corner_offset[c][2] = (c >> 2) & 1;

#pragma omp parallel
  {
    std::vector<float> pad(static_cast<std::size_t>(P) * P * P);
    std::vector<std::int32_t> local(static_cast<std::size_t>(B) * B * B * 3, -1);  // key -> vertex of this block
#pragma omp for schedule(dynamic, 1)
    for (std::size_t o = 0; o < nb; ++o) {
      const std::size_t sl = order[o];
      const long bc[3] = {f.slot_block[0][sl], f.slot_block[1][sl], f.slot_block[2][sl]};
      f.padded(bc[0], bc[1], bc[2], pad.data());
      BlockPiece& piece = pieces[o];
      // The vertices: one on each edge from a voxel of the block along +x, +y, +z that the
      // surface crosses, in the order of their keys.
      for (int k = 0; k < B; ++k)
        for (int j = 0; j < B; ++j)
          for (int i = 0; i < B; ++i) {
            const int at = padded_at(i, j, k);
            const bool in = pad[at] > iso;
            for (int a = 0; a < 3; ++a) {
              if ((pad[at + step[a]] > iso) == in) continue;
              const EdgeKey key = static_cast<EdgeKey>(((k * B + j) * B + i) * 3 + a);
              local[key] = static_cast<std::int32_t>(piece.keys.size());
              piece.keys.push_back(key);
              const int l[3] = {i, j, k};
              const double phi_p = pad[at], phi_q = pad[at + step[a]];
              const double t = std::clamp((s.iso - phi_p) / (phi_q - phi_p), 1e-3, 1 - 1e-3);
              std::array<double, 3> x;
              double grad[3];
              for (int c = 0; c < 3; ++c) {
                x[c] = f.centre(c, bc[c] * B + l[c]) + (c == a ? t * f.v[c] : 0.0);
                const double gp = (pad[at + step[c]] - pad[at - step[c]]) / (2 * f.v[c]);
                const double gq = (pad[at + step[a] + step[c]] - pad[at + step[a] - step[c]]) / (2 * f.v[c]);
                grad[c] = (1 - t) * gp + t * gq;
              }
              double len = std::sqrt(grad[0] * grad[0] + grad[1] * grad[1] + grad[2] * grad[2]);
              if (!(len > 0)) {  // flat: the edge's own direction
                grad[0] = grad[1] = grad[2] = 0, grad[a] = phi_q - phi_p, len = std::fabs(grad[a]);
              }
              piece.vertices.push_back(x);
              piece.normals.push_back({static_cast<float>(-grad[0] / len), static_cast<float>(-grad[1] / len),
                                       static_cast<float>(-grad[2] / len)});
              const long g = bc[a] * B + l[a];
              piece.on_wall.push_back((s.wall[2 * a] && g == -1) || (s.wall[2 * a + 1] && g == f.n[a] - 1));
            }
          }
      // The triangles of the cubes whose lower corner is in the block; a corner on an edge of a
      // block above is named by that block and the edge's key there.
      auto corner = [&](int q0, int q1, int q2, int a) -> std::uint32_t {
        if (q0 < B && q1 < B && q2 < B) return static_cast<std::uint32_t>(local[((q2 * B + q1) * B + q0) * 3 + a]);
        const int up[3] = {q0 >= B, q1 >= B, q2 >= B};
        const int key = (((q2 - up[2] * B) * B + (q1 - up[1] * B)) * B + (q0 - up[0] * B)) * 3 + a;
        return static_cast<std::uint32_t>(((up[0] | up[1] << 1 | up[2] << 2) << 16) | key);
      };
      for (int k = 0; k < B; ++k)
        for (int j = 0; j < B; ++j)
          for (int i = 0; i < B; ++i) {
            const int at = padded_at(i, j, k);
            int mask = 0;
            for (int c = 0; c < 8; ++c)
              if (pad[at + corner_offset[c][0] + corner_offset[c][1] * P + corner_offset[c][2] * P * P] > iso) mask |= 1 << c;
            const int count = cases.triangles[mask];
            for (int t = 0; t < count; ++t) {
              std::array<std::uint32_t, 3> tri;
              for (int v = 0; v < 3; ++v) {
                const int e = cases.edges[mask][3 * t + v], c = edge_corner(e);
                tri[v] = corner(i + corner_offset[c][0], j + corner_offset[c][1], k + corner_offset[c][2], edge_axis(e));
              }
              piece.corners.push_back(tri);
            }
          }
      for (const EdgeKey key : piece.keys) local[key] = -1;
    }
  }

  SurfacePiece out;
  out.blocks.resize(nb);
  out.first_vertex.resize(nb + 1, 0);
  out.first_triangle.resize(nb + 1, 0);
  for (std::size_t o = 0; o < nb; ++o) {
    for (int c = 0; c < 3; ++c) out.blocks[o][c] = f.slot_block[c][order[o]];
    if (out.first_vertex[o] + pieces[o].keys.size() > UINT32_MAX)
      throw Error("the surface has more than 4.29 x 10^9 vertices: raise the voxel size");
    out.first_vertex[o + 1] = out.first_vertex[o] + static_cast<std::uint32_t>(pieces[o].keys.size());
    out.first_triangle[o + 1] = out.first_triangle[o] + static_cast<std::uint32_t>(pieces[o].corners.size());
  }
  auto append = [](auto& to, const auto& from) { to.insert(to.end(), from.begin(), from.end()); };
  for (auto& piece : pieces) {
    append(out.keys, piece.keys);
    append(out.vertices, piece.vertices);
    append(out.normals, piece.normals);
    append(out.on_wall, piece.on_wall);
    append(out.corners, piece.corners);
    piece = BlockPiece{};
  }
  return out;
}

}  // namespace pbf
