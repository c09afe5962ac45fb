#pragma once
// A surface as triangles: vertex positions and, per triangle, three vertex indices ordered
// counter-clockwise seen from outside (the right-hand normal points out of the solid).
#include <array>
#include <cstdint>
#include <vector>

namespace pbf {

struct TriangleMesh {
  std::vector<std::array<double, 3>> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

// Where a solid goes: its mesh (or primitive) is scaled by `scale` about the origin (along
// x, y and z), rotated by `rotate_deg` (degrees about x, then y, then z, fixed axes) and moved
// by `translate`.
struct Placement {
  std::array<double, 3> scale{1, 1, 1};
  std::array<double, 3> rotate_deg{0, 0, 0};
  std::array<double, 3> translate{0, 0, 0};
};

}  // namespace pbf
