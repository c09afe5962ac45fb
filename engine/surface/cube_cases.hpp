#pragma once
// The 256 cases of marching cubes (Lorensen & Cline 1987): for each pattern of corners inside
// the surface, the triangles that cut the cube, as triples of the cube's edges (a vertex lies
// on each edge the surface crosses).
//
// The table is built, not typed in (engine/surface/cube_cases.cpp): on each face of the cube
// the crossings are joined into segments around each run of consecutive inside corners, so
// a face with two diagonal inside corners (the ambiguous face) always cuts them apart. That
// choice depends on the face's four corners alone, so the two cubes that share a face join
// its crossings alike and the mesh has no cracks (the original table's complementary cases
// did not). The segments chain into closed loops around the cube, and each loop is fanned into
// triangles, oriented so that their right-hand normal points out of the inside region.
//
// Corners: c = x + 2 y + 4 z for x, y, z in {0, 1}. Edges: 4 a + k along axis a (0 x, 1 y,
// 2 z) from the k-th corner, in order of c, whose coordinate along a is 0.
#include <array>
#include <cstdint>

namespace pbf {

struct CubeCases {
  static constexpr int kMaxTriangles = 10;
  std::array<std::uint8_t, 256> triangles{};                          // how many, per case
  std::array<std::array<std::int8_t, 3 * kMaxTriangles>, 256> edges{};  // three edges each
};

// The table (built once).
const CubeCases& cube_cases();

// The lower corner of edge e (0 to 11) and its axis.
int edge_corner(int e);
inline int edge_axis(int e) { return e / 4; }

}  // namespace pbf
