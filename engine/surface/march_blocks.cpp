// Marching cubes over the blocks of voxels. Every edge the surface crosses is one vertex,
// owned by the block that holds the edge's lower voxel. Two passes over the blocks, in
// parallel: the first lists each block's crossed edges (so that a prefix sum numbers the
// vertices block by block, in a fixed order), the second makes the block's vertices and the
// triangles of the cubes whose lower corner it holds, finding a vertex on an edge of the next
// block up by a binary search in that block's list. Cubes follow engine/surface/cube_cases.
#include <algorithm>
#include <atomic>
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

SurfaceMesh march_blocks(const VoxelBlocks& f, const SurfaceSettings& s) {
  const std::size_t slots = f.slots();
  const float iso = static_cast<float>(s.iso);
  const int step[3] = {1, P, P * P};

  // Pass 1: each block's crossed edges, in order of their keys.
  std::vector<std::vector<EdgeKey>> keys(slots);
#pragma omp parallel
  {
    std::vector<float> pad(static_cast<std::size_t>(P) * P * P);
#pragma omp for schedule(dynamic, 1)
    for (std::size_t sl = 0; sl < slots; ++sl) {
      f.padded(f.slot_block[0][sl], f.slot_block[1][sl], f.slot_block[2][sl], pad.data());
      auto& list = keys[sl];
      for (int k = 0; k < B; ++k)
        for (int j = 0; j < B; ++j)
          for (int i = 0; i < B; ++i) {
            const int at = padded_at(i, j, k);
            const bool in = pad[at] > iso;
            for (int a = 0; a < 3; ++a)
              if ((pad[at + step[a]] > iso) != in) list.push_back(static_cast<EdgeKey>(((k * B + j) * B + i) * 3 + a));
          }
    }
  }
  std::vector<std::uint32_t> first_vertex(slots + 1, 0);
  for (std::size_t sl = 0; sl < slots; ++sl) {
    if (first_vertex[sl] + keys[sl].size() > UINT32_MAX)
      throw Error("the surface has more than 4.29 x 10^9 vertices: raise the voxel size");
    first_vertex[sl + 1] = first_vertex[sl] + static_cast<std::uint32_t>(keys[sl].size());
  }

  SurfaceMesh out;
  const std::size_t nv = first_vertex[slots];
  out.mesh.vertices.resize(nv);
  out.normals.resize(nv);
  std::vector<char> on_wall(s.walls == SurfaceWalls::open ? nv : 0, 0);
  std::vector<std::vector<std::array<std::uint32_t, 3>>> triangles(slots);
  const CubeCases& cases = cube_cases();
  int corner_offset[8][3];
  for (int c = 0; c < 8; ++c) corner_offset[c][0] = c & 1, corner_offset[c][1] = (c >> 1) & 1, corner_offset[c][2] = (c >> 2) & 1;

  // Pass 2: vertices and triangles.
  std::atomic<bool> broken = false;
#pragma omp parallel
  {
    std::vector<float> pad(static_cast<std::size_t>(P) * P * P);
    std::vector<std::int32_t> local(static_cast<std::size_t>(B) * B * B * 3, -1);  // key -> vertex of this block
#pragma omp for schedule(dynamic, 1)
    for (std::size_t sl = 0; sl < slots; ++sl) {
      const long bc[3] = {f.slot_block[0][sl], f.slot_block[1][sl], f.slot_block[2][sl]};
      f.padded(bc[0], bc[1], bc[2], pad.data());
      const auto& list = keys[sl];
      for (std::size_t m = 0; m < list.size(); ++m) {
        const int key = list[m], a = key % 3, voxel = key / 3;
        const int l[3] = {voxel % B, (voxel / B) % B, voxel / (B * B)};
        const int at = padded_at(l[0], l[1], l[2]);
        const double phi_p = pad[at], phi_q = pad[at + step[a]];
        const double t = std::clamp((s.iso - phi_p) / (phi_q - phi_p), 1e-3, 1 - 1e-3);
        const std::uint32_t vi = first_vertex[sl] + static_cast<std::uint32_t>(m);
        local[key] = static_cast<std::int32_t>(vi);
        auto& x = out.mesh.vertices[vi];
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
        for (int c = 0; c < 3; ++c) out.normals[vi][c] = static_cast<float>(-grad[c] / len);
        if (!on_wall.empty()) {
          const long g = bc[a] * B + l[a];
          on_wall[vi] = (s.wall[2 * a] && g == -1) || (s.wall[2 * a + 1] && g == f.n[a] - 1);
        }
      }
      // The vertex on the cube edge from local voxel q along axis a.
      auto vertex = [&](int q0, int q1, int q2, int a) -> std::uint32_t {
        if (q0 < B && q1 < B && q2 < B) return static_cast<std::uint32_t>(local[((q2 * B + q1) * B + q0) * 3 + a]);
        const int up[3] = {q0 >= B, q1 >= B, q2 >= B};
        const std::int32_t other = f.slot(bc[0] + up[0], bc[1] + up[1], bc[2] + up[2]);
        if (other < 0) {  // cannot happen: the blocks reach a voxel below every kernel
          broken = true;
          return 0;
        }
        const EdgeKey key = static_cast<EdgeKey>((((q2 - up[2] * B) * B + (q1 - up[1] * B)) * B + (q0 - up[0] * B)) * 3 + a);
        const auto& theirs = keys[static_cast<std::size_t>(other)];
        const auto it = std::lower_bound(theirs.begin(), theirs.end(), key);
        return first_vertex[static_cast<std::size_t>(other)] + static_cast<std::uint32_t>(it - theirs.begin());
      };
      auto& tris = triangles[sl];
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
                tri[v] = vertex(i + corner_offset[c][0], j + corner_offset[c][1], k + corner_offset[c][2], edge_axis(e));
              }
              tris.push_back(tri);
            }
          }
      for (const EdgeKey key : list) local[key] = -1;
    }
  }

  if (broken) throw Error("internal error: the surface crosses into a block of voxels that was not computed");
  std::size_t total = 0;
  for (const auto& t : triangles) total += t.size();
  out.mesh.triangles.reserve(total);
  for (const auto& t : triangles)
    for (const auto& tri : t)
      if (on_wall.empty() || !(on_wall[tri[0]] && on_wall[tri[1]] && on_wall[tri[2]])) out.mesh.triangles.push_back(tri);
  if (!on_wall.empty()) {  // open walls: drop the vertices only the wetted walls used
    std::vector<std::uint32_t> renumber(nv, UINT32_MAX);
    for (const auto& tri : out.mesh.triangles)
      for (std::uint32_t v : tri) renumber[v] = 0;
    std::uint32_t kept = 0;
    for (std::size_t v = 0; v < nv; ++v)
      if (renumber[v] == 0) {
        renumber[v] = kept;
        out.mesh.vertices[kept] = out.mesh.vertices[v];
        out.normals[kept] = out.normals[v];
        ++kept;
      }
    out.mesh.vertices.resize(kept);
    out.normals.resize(kept);
    for (auto& tri : out.mesh.triangles)
      for (std::uint32_t& v : tri) v = renumber[v];
  }
  return out;
}

}  // namespace pbf
