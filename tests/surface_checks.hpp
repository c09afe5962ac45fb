#pragma once
// Checks of a triangle mesh that a renderer relies on: closed and manifold (every edge in two
// triangles, once each way: outward orientation is consistent), each vertex's triangles one fan,
// no two triangles crossing; and its enclosed volume (divergence theorem).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

#include "engine/geometry/triangle_mesh.hpp"

namespace pbf::surface_checks {

using Vec = std::array<double, 3>;
inline Vec sub(const Vec& a, const Vec& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline Vec cross(const Vec& a, const Vec& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double dot(const Vec& a, const Vec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// The volume the mesh encloses (positive for outward triangles).
inline double enclosed_volume(const TriangleMesh& m) {
  double v = 0;
  for (const auto& t : m.triangles) v += dot(m.vertices[t[0]], cross(m.vertices[t[1]], m.vertices[t[2]]));
  return v / 6;
}

// "" if every directed edge appears once and its reverse once, and each vertex's triangles
// form one fan; else what is wrong. `boundary_ok`: edges without a twin are allowed (an open
// surface), but none may appear twice.
inline std::string manifold_defect(const TriangleMesh& m, bool boundary_ok = false) {
  std::unordered_map<std::uint64_t, int> directed;
  auto key = [](std::uint32_t a, std::uint32_t b) { return (std::uint64_t(a) << 32) | b; };
  for (const auto& t : m.triangles) {
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) return "a triangle repeats a vertex";
    for (int k = 0; k < 3; ++k)
      if (++directed[key(t[k], t[(k + 1) % 3])] > 1) return "an edge is used twice the same way (orientation flips)";
  }
  if (!boundary_ok)
    for (const auto& [k, count] : directed)
      if (!directed.count((k << 32) | (k >> 32))) return "an edge has one triangle (a hole)";
  // Each vertex: the edges opposite it, b -> c for triangle (v, b, c), must chain into one cycle.
  std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>> fans(m.vertices.size());
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) fans[t[k]].push_back({t[(k + 1) % 3], t[(k + 2) % 3]});
  for (std::size_t v = 0; v < fans.size(); ++v) {
    auto& fan = fans[v];
    if (fan.empty()) continue;
    std::map<std::uint32_t, std::uint32_t> next;
    for (auto [b, c] : fan) next[b] = c;
    std::uint32_t start = fan[0].first, at = start;
    std::size_t steps = 0;
    if (boundary_ok) continue;
    do {
      auto it = next.find(at);
      if (it == next.end()) return "a vertex's triangles do not close around it";
      at = it->second;
      ++steps;
    } while (at != start && steps <= fan.size());
    if (steps != fan.size()) return "a vertex joins two fans (pinched)";
  }
  return "";
}

namespace detail {
// Whether segment p-q crosses triangle (a, b, c) at an interior point of both.
inline bool segment_crosses(const Vec& p, const Vec& q, const Vec& a, const Vec& b, const Vec& c) {
  const Vec e1 = sub(b, a), e2 = sub(c, a), d = sub(q, p);
  const Vec h = cross(d, e2);
  const double det = dot(e1, h);
  const double scale = std::sqrt(dot(e1, e1) * dot(e2, e2) * dot(d, d));
  if (std::fabs(det) <= 1e-12 * scale) return false;  // parallel (coplanar contact is not counted)
  const double inv = 1 / det;
  const Vec s = sub(p, a);
  const double u = dot(s, h) * inv;
  const Vec qq = cross(s, e1);
  const double v = dot(d, qq) * inv, t = dot(e2, qq) * inv;
  constexpr double eps = 1e-9;
  return u > eps && v > eps && u + v < 1 - eps && t > eps && t < 1 - eps;
}
}  // namespace detail

// How many pairs of triangles that share no edge cross each other (edges through the
// other's interior), found through a hash of cells `cell` wide.
inline std::size_t self_intersections(const TriangleMesh& m, double cell) {
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells;
  auto cell_key = [](long i, long j, long k) {
    return (std::uint64_t(i & 0x1fffff) << 42) | (std::uint64_t(j & 0x1fffff) << 21) | std::uint64_t(k & 0x1fffff);
  };
  for (std::uint32_t t = 0; t < m.triangles.size(); ++t) {
    long lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      double mn = 1e300, mx = -1e300;
      for (int k = 0; k < 3; ++k) mn = std::min(mn, m.vertices[m.triangles[t][k]][a]), mx = std::max(mx, m.vertices[m.triangles[t][k]][a]);
      lo[a] = static_cast<long>(std::floor(mn / cell)), hi[a] = static_cast<long>(std::floor(mx / cell));
    }
    for (long i = lo[0]; i <= hi[0]; ++i)
      for (long j = lo[1]; j <= hi[1]; ++j)
        for (long k = lo[2]; k <= hi[2]; ++k) cells[cell_key(i, j, k)].push_back(t);
  }
  std::size_t found = 0;
  std::unordered_map<std::uint64_t, bool> seen;
  for (const auto& [k, list] : cells)
    for (std::size_t x = 0; x < list.size(); ++x)
      for (std::size_t y = x + 1; y < list.size(); ++y) {
        const auto& A = m.triangles[list[x]];
        const auto& Bt = m.triangles[list[y]];
        int shared = 0;
        for (auto a : A)
          for (auto b : Bt) shared += a == b;
        if (shared >= 2) continue;
        const std::uint64_t pair = (std::uint64_t(std::min(list[x], list[y])) << 32) | std::max(list[x], list[y]);
        if (seen.count(pair)) continue;
        seen[pair] = true;
        auto crosses = [&](const std::array<std::uint32_t, 3>& s, const std::array<std::uint32_t, 3>& t) {
          for (int e = 0; e < 3; ++e) {
            const auto p = s[e], q = s[(e + 1) % 3];
            if (p == t[0] || p == t[1] || p == t[2] || q == t[0] || q == t[1] || q == t[2]) continue;
            if (detail::segment_crosses(m.vertices[p], m.vertices[q], m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]]))
              return true;
          }
          return false;
        };
        if (crosses(A, Bt) || crosses(Bt, A)) ++found;
      }
  return found;
}

}  // namespace pbf::surface_checks
