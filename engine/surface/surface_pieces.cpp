// join_surface_pieces: the parts' pieces (engine/surface/surface.hpp) as one mesh. The blocks of
// all pieces in (z, y, x) order number the vertices, block after block, each block's in the
// order of their edges; a triangle's corner in a block above is found by that block's
// coordinates and a binary search for the edge's key in its list. The order depends on the
// blocks alone, not on how they were parted: one part or many give the same bits. Walls open,
// the triangles that lie on a wall face are left out, and the vertices only they used.
// SurfaceSlabs cuts the domain into parts and says which particles each needs.
#include <algorithm>
#include <cmath>

#include "engine/core/error.hpp"
#include "engine/surface/surface_parts.hpp"

namespace pbf {

namespace {

using Block = std::array<std::int64_t, 3>;

bool before(const Block& a, const Block& b) {
  return a[2] != b[2] ? a[2] < b[2] : (a[1] != b[1] ? a[1] < b[1] : a[0] < b[0]);
}

}  // namespace

SurfaceMesh join_surface_pieces(const std::vector<SurfacePiece>& pieces, const SurfaceSettings& s) {
  // Every block: its piece and its index there, in (z, y, x) order.
  struct Entry {
    Block block;
    std::uint32_t piece, index;
  };
  std::vector<Entry> blocks;
  for (std::size_t p = 0; p < pieces.size(); ++p)
    for (std::size_t b = 0; b < pieces[p].blocks.size(); ++b)
      blocks.push_back({pieces[p].blocks[b], static_cast<std::uint32_t>(p), static_cast<std::uint32_t>(b)});
  std::sort(blocks.begin(), blocks.end(), [](const Entry& a, const Entry& b) { return before(a.block, b.block); });
  const std::size_t nb = blocks.size();
  std::vector<std::uint64_t> first_vertex(nb + 1, 0), first_triangle(nb + 1, 0);
  for (std::size_t k = 0; k < nb; ++k) {
    const SurfacePiece& piece = pieces[blocks[k].piece];
    const std::uint32_t b = blocks[k].index;
    first_vertex[k + 1] = first_vertex[k] + (piece.first_vertex[b + 1] - piece.first_vertex[b]);
    first_triangle[k + 1] = first_triangle[k] + (piece.first_triangle[b + 1] - piece.first_triangle[b]);
  }
  if (first_vertex[nb] > UINT32_MAX) throw Error("the surface has more than 4.29 x 10^9 vertices: raise the voxel size");
  const std::size_t nv = first_vertex[nb];

  SurfaceMesh out;
  out.mesh.vertices.resize(nv);
  out.normals.resize(nv);
  std::vector<std::uint8_t> on_wall(nv);
  if (!pieces.empty())
    for (const auto& a : pieces.front().attributes)
      out.attributes.push_back({a.name, a.components, std::vector<double>(nv * static_cast<std::size_t>(a.components))});
  out.mesh.triangles.resize(first_triangle[nb]);
  bool broken = false;
#pragma omp parallel for schedule(dynamic, 16) reduction(|| : broken)
  for (std::size_t k = 0; k < nb; ++k) {
    const SurfacePiece& piece = pieces[blocks[k].piece];
    const std::uint32_t b = blocks[k].index;
    const std::size_t v0 = piece.first_vertex[b], count = piece.first_vertex[b + 1] - v0;
    for (std::size_t v = 0; v < count; ++v) {
      out.mesh.vertices[first_vertex[k] + v] = piece.vertices[v0 + v];
      out.normals[first_vertex[k] + v] = piece.normals[v0 + v];
      on_wall[first_vertex[k] + v] = piece.on_wall[v0 + v];
    }
    for (std::size_t a = 0; a < out.attributes.size(); ++a) {
      const auto& from = piece.attributes[a];
      auto& to = out.attributes[a];
      const std::size_t piece_nv = piece.vertices.size();
      for (int c = 0; c < from.components; ++c)
        for (std::size_t v = 0; v < count; ++v)
          to.values[static_cast<std::size_t>(c) * nv + first_vertex[k] + v] =
              from.values[static_cast<std::size_t>(c) * piece_nv + v0 + v];
    }
    // The vertex a corner names.
    auto vertex = [&](std::uint32_t corner) -> std::uint32_t {
      const std::uint32_t up = corner >> 16, low = corner & 0xffff;
      if (up == 0) return static_cast<std::uint32_t>(first_vertex[k] + low);
      const Block above = {blocks[k].block[0] + (up & 1), blocks[k].block[1] + ((up >> 1) & 1),
                           blocks[k].block[2] + ((up >> 2) & 1)};
      const auto it = std::lower_bound(blocks.begin(), blocks.end(), above,
                                       [](const Entry& e, const Block& x) { return before(e.block, x); });
      if (it == blocks.end() || it->block != above) {  // cannot happen: the blocks reach a voxel below every kernel
        broken = true;
        return 0;
      }
      const SurfacePiece& theirs = pieces[it->piece];
      const auto first = theirs.keys.begin() + theirs.first_vertex[it->index];
      const auto last = theirs.keys.begin() + theirs.first_vertex[it->index + 1];
      const auto at = std::lower_bound(first, last, static_cast<std::uint16_t>(low));
      if (at == last || *at != low) {
        broken = true;
        return 0;
      }
      return static_cast<std::uint32_t>(first_vertex[static_cast<std::size_t>(it - blocks.begin())] + (at - first));
    };
    const std::size_t t0 = piece.first_triangle[b], triangles = piece.first_triangle[b + 1] - t0;
    for (std::size_t t = 0; t < triangles; ++t)
      for (int c = 0; c < 3; ++c) out.mesh.triangles[first_triangle[k] + t][c] = vertex(piece.corners[t0 + t][c]);
  }
  if (broken) throw Error("internal error: the surface crosses into a block of voxels that was not computed");

  if (s.walls == SurfaceWalls::open) {  // the wetted walls left out, and the vertices only they used
    std::size_t kept_triangles = 0;
    for (const auto& tri : out.mesh.triangles)
      if (!(on_wall[tri[0]] && on_wall[tri[1]] && on_wall[tri[2]])) out.mesh.triangles[kept_triangles++] = tri;
    out.mesh.triangles.resize(kept_triangles);
    std::vector<std::uint32_t> renumber(nv, UINT32_MAX);
    for (const auto& tri : out.mesh.triangles)
      for (std::uint32_t v : tri) renumber[v] = 0;
    std::uint32_t kept = 0;
    for (std::size_t v = 0; v < nv; ++v)
      if (renumber[v] == 0) {
        renumber[v] = kept;
        out.mesh.vertices[kept] = out.mesh.vertices[v];
        out.normals[kept] = out.normals[v];
        for (auto& a : out.attributes)
          for (int c = 0; c < a.components; ++c)
            a.values[static_cast<std::size_t>(c) * nv + kept] = a.values[static_cast<std::size_t>(c) * nv + v];
        ++kept;
      }
    out.mesh.vertices.resize(kept);
    out.normals.resize(kept);
    for (auto& a : out.attributes) {  // component-major: each component's run moves down to its new place
      for (int c = 1; c < a.components; ++c)
        std::copy_n(a.values.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(c) * nv), kept,
                    a.values.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(c) * kept));
      a.values.resize(static_cast<std::size_t>(a.components) * kept);
    }
    for (auto& tri : out.mesh.triangles)
      for (std::uint32_t& v : tri) v = renumber[v];
  }
  return out;
}

SurfaceSlabs::SurfaceSlabs(const SurfaceSettings& s, bool mirrors) {
  // The longest axis that is not periodic (the smoothing reads across a periodic face the far
  // side's voxels, which another slab holds); with none, one part meshes everything.
  axis = -1;
  for (int a = 0; a < 3; ++a)
    if (!s.periodic[a] && (axis < 0 || s.hi[a] - s.lo[a] > s.hi[axis] - s.lo[axis])) axis = a;
  whole_ = axis < 0;
  if (whole_) axis = 0;
  lo_ = s.lo[axis], hi_ = s.hi[axis];
  const long voxels = std::max(1L, std::lround((hi_ - lo_) / s.voxel));  // as VoxelBlocks divides the domain
  voxel_ = (hi_ - lo_) / static_cast<double>(voxels);
  layers = (voxels + VoxelBlocks::kBlock - 1) / VoxelBlocks::kBlock;
  // A kernel that decides an owned block's status (its box grown by a voxel below and the
  // band's two) or that reaches the ring's layers that the smoothing and the cubes read (the
  // passes and two): R and that many voxels; a solid's image lies up to 2 R from its particle;
  // and a kernel's sums read the neighbour cells on either side of its own, whole.
  const double cell = (hi_ - lo_) / std::max(1.0, std::floor((hi_ - lo_) / s.radius));  // as GridGeometry::of
  reach_ = s.radius + (std::max(s.smoothing, 1) + 3) * voxel_ + (mirrors ? 2 * s.radius : 0.0) + 2 * cell;
  first_ = {0, layers};
}

long SurfaceSlabs::layer(double x) const {
  const double voxel = std::clamp(std::floor((x - lo_) / voxel_), 0.0, static_cast<double>(layers) * VoxelBlocks::kBlock - 1);
  return static_cast<long>(voxel) / VoxelBlocks::kBlock;
}

void SurfaceSlabs::cut(const std::vector<std::int64_t>& count, int parts) {
  std::int64_t total = 0;
  for (auto c : count) total += c;
  first_.assign(static_cast<std::size_t>(parts) + 1, layers);
  std::int64_t below = 0;
  long l = 0;
  for (int r = 0; r < parts; ++r) {
    first_[static_cast<std::size_t>(r)] = l;
    const std::int64_t target = total * (r + 1) / parts;
    while (l < layers && below + count[static_cast<std::size_t>(l)] <= target) below += count[static_cast<std::size_t>(l++)];
  }
}

SurfacePart SurfaceSlabs::part(int r) const {
  SurfacePart p;
  p.axis = axis;
  if (whole_) {  // the first part everything, the others nothing
    if (r > 0) p.first = p.end;
    return p;
  }
  const std::size_t parts = first_.size() - 1, k = static_cast<std::size_t>(r);
  if (k > 0) p.first = first_[k];
  if (k + 1 < parts) p.end = first_[k + 1];
  return p;
}

bool SurfaceSlabs::needs(int r, double x) const {
  if (whole_) return r == 0;
  const std::size_t k = static_cast<std::size_t>(r);
  const double B = VoxelBlocks::kBlock;
  // (A particle beyond the domain counts where the neighbour cells put it: at its face.)
  const double at = std::clamp(x, lo_, hi_);
  return at >= lo_ + static_cast<double>(first_[k]) * B * voxel_ - reach_ &&
         at <= lo_ + static_cast<double>(first_[k + 1]) * B * voxel_ + reach_;
}

}  // namespace pbf
