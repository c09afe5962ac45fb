#include "engine/surface/cube_cases.hpp"

#include <vector>

namespace pbf {

namespace {

// The corners whose coordinate along `axis` is 0, in order of their number.
int lower_corner(int axis, int k) {
  int found = 0;
  for (int c = 0; c < 8; ++c)
    if (!((c >> axis) & 1) && found++ == k) return c;
  return -1;
}

}  // namespace

int edge_corner(int e) { return lower_corner(e / 4, e % 4); }

namespace {

// The edge joining corners a and b (which differ along one axis).
int edge_between(int a, int b) {
  const int axis = (a ^ b) == 1 ? 0 : ((a ^ b) == 2 ? 1 : 2);
  const int low = a < b ? a : b;
  for (int k = 0; k < 4; ++k)
    if (lower_corner(axis, k) == low) return 4 * axis + k;
  return -1;
}

// Whether edges a, b and c all lie on one face of the cube (each edge lies on two: for each
// other axis, the side its corner is on).
bool on_one_face(int a, int b, int c) {
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      auto on = [&](int e) { return edge_axis(e) != axis && ((edge_corner(e) >> axis) & 1) == side; };
      if (on(a) && on(b) && on(c)) return true;
    }
  return false;
}

CubeCases build() {
  CubeCases table;
  for (int mask = 0; mask < 256; ++mask) {
    auto inside = [&](int c) { return (mask >> c) & 1; };
    // next[e]: the crossing that follows e on its loop (-1: e not crossed).
    int next[12];
    for (int& n : next) n = -1;
    for (int axis = 0; axis < 3; ++axis)
      for (int side = 0; side < 2; ++side) {
        // The face's corners in the order that turns counter-clockwise about its outward
        // normal: (u, w) = (0,0), (1,0), (1,1), (0,1) turns about +axis for the axes u, w
        // that follow it; the lower face (normal -axis) goes the other way.
        const int u = (axis + 1) % 3, w = (axis + 2) % 3;
        const int uw[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
        int p[4];
        for (int k = 0; k < 4; ++k) {
          const int kk = side ? k : 3 - k;
          p[k] = (side << axis) | (uw[kk][0] << u) | (uw[kk][1] << w);
        }
        // Each run of consecutive inside corners p[k..m] gives one segment, from the edge where
        // the run begins (entering it) to the edge where it ends (leaving it): the inside
        // corners lie to its right seen from outside the cube.
        for (int k = 0; k < 4; ++k) {
          const int prev = p[(k + 3) % 4];
          if (!inside(p[k]) || inside(prev)) continue;  // k starts a run
          int m = k;
          while (inside(p[(m + 1) % 4])) m = (m + 1) % 4;
          next[edge_between(prev, p[k])] = edge_between(p[m], p[(m + 1) % 4]);
        }
      }
    // Chain the segments into loops and fan each loop into triangles. Walking a loop with the
    // inside to the right seen from outside the cube, the fan's right-hand normal points away
    // from the inside corners: out of the fluid.
    bool used[12] = {};
    std::vector<std::int8_t> tris;
    for (int start = 0; start < 12; ++start) {
      if (next[start] < 0 || used[start]) continue;
      std::vector<int> loop;
      for (int e = start; !used[e]; e = next[e]) {
        used[e] = true;
        loop.push_back(e);
      }
      // The fan's apex: the first vertex from which no triangle lies flat on a face of the
      // cube (a loop that crosses an ambiguous face twice has two segments there; a triangle
      // joining them would lie in the face, and the neighbouring cube's would lie on it).
      const std::size_t m = loop.size();
      std::size_t apex = 0;
      for (std::size_t r = 0; r < m; ++r) {
        bool flat = false;
        for (std::size_t k = 1; k + 1 < m; ++k)
          flat |= on_one_face(loop[r], loop[(r + k) % m], loop[(r + k + 1) % m]);
        if (!flat) {
          apex = r;
          break;
        }
      }
      for (std::size_t k = 1; k + 1 < m; ++k) {
        tris.push_back(static_cast<std::int8_t>(loop[apex]));
        tris.push_back(static_cast<std::int8_t>(loop[(apex + k) % m]));
        tris.push_back(static_cast<std::int8_t>(loop[(apex + k + 1) % m]));
      }
    }
    table.triangles[mask] = static_cast<std::uint8_t>(tris.size() / 3);
    for (std::size_t k = 0; k < tris.size(); ++k) table.edges[mask][k] = tris[k];
  }
  return table;
}

}  // namespace

const CubeCases& cube_cases() {
  static const CubeCases table = build();
  return table;
}

}  // namespace pbf
