#include "engine/geometry/primitives.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <map>
#include <numbers>
#include <utility>

#include "engine/core/error.hpp"

namespace pbf {

namespace {

using Vec = std::array<double, 3>;
using Tri = std::array<std::uint32_t, 3>;

Vec add(const Vec& a, const Vec& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
Vec sub(const Vec& a, const Vec& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec mul(double s, const Vec& a) { return {s * a[0], s * a[1], s * a[2]}; }
double dot(const Vec& a, const Vec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec cross(const Vec& a, const Vec& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double norm(const Vec& a) { return std::sqrt(dot(a, a)); }

void require_positive(const char* function, const char* what, double value) {
  if (!(value > 0) || !std::isfinite(value))
    throw Error(fmt::format("{}: {} must be positive and finite, not {}", function, what, value));
}

void require_box(const char* function, const Vec& lo, const Vec& hi) {
  for (int d = 0; d < 3; ++d)
    if (!(lo[d] < hi[d]) || !std::isfinite(lo[d]) || !std::isfinite(hi[d]))
      throw Error(fmt::format("{}: lo ({}, {}, {}) must be below hi ({}, {}, {}) on every axis", function, lo[0],
                              lo[1], lo[2], hi[0], hi[1], hi[2]));
}

// Two unit vectors that make a right-handed frame (e1, e2, axis) with the unit vector `axis`.
std::pair<Vec, Vec> frame_around(const Vec& axis) {
  int least = 0;  // the coordinate axis least aligned with `axis` gives a well-conditioned cross product
  for (int d = 1; d < 3; ++d)
    if (std::abs(axis[d]) < std::abs(axis[least])) least = d;
  Vec helper{0, 0, 0};
  helper[least] = 1;
  const Vec e1 = mul(1 / norm(cross(axis, helper)), cross(axis, helper));
  return {e1, cross(axis, e1)};
}

double longest_edge(const TriangleMesh& m) {
  double longest = 0;
  for (const Tri& t : m.triangles)
    for (int k = 0; k < 3; ++k) longest = std::max(longest, norm(sub(m.vertices[t[k]], m.vertices[t[(k + 1) % 3]])));
  return longest;
}

// Splits every triangle of a unit icosphere into four at its edges' midpoints, pushed out to
// the sphere; a midpoint is made once and shared by the two triangles of its edge.
TriangleMesh subdivide(const TriangleMesh& m) {
  TriangleMesh out{m.vertices, {}};
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> midpoints;
  auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
    const auto [it, added] = midpoints.try_emplace({std::min(a, b), std::max(a, b)}, 0);
    if (added) {
      const Vec mid = add(out.vertices[a], out.vertices[b]);
      it->second = static_cast<std::uint32_t>(out.vertices.size());
      out.vertices.push_back(mul(1 / norm(mid), mid));
    }
    return it->second;
  };
  for (const Tri& t : m.triangles) {
    const std::uint32_t ab = midpoint(t[0], t[1]), bc = midpoint(t[1], t[2]), ca = midpoint(t[2], t[0]);
    out.triangles.insert(out.triangles.end(), {{t[0], ab, ca}, {ab, t[1], bc}, {ca, bc, t[2]}, {ab, bc, ca}});
  }
  return out;
}

}  // namespace

TriangleMesh box_mesh(const Vec& lo, const Vec& hi) {
  require_box("box_mesh", lo, hi);
  TriangleMesh m;
  for (int i = 0; i < 8; ++i)  // corner i is x + 2y + 4z, 0 meaning lo and 1 hi
    m.vertices.push_back({i & 1 ? hi[0] : lo[0], i & 2 ? hi[1] : lo[1], i & 4 ? hi[2] : lo[2]});
  // Each face's corners counter-clockwise seen from outside: -z, +z, -y, +y, -x, +x.
  constexpr std::uint32_t kFaces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                          {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : kFaces) m.triangles.insert(m.triangles.end(), {{f[0], f[1], f[2]}, {f[0], f[2], f[3]}});
  return m;
}

TriangleMesh sphere_mesh(const Vec& center, double radius, double max_edge) {
  require_positive("sphere_mesh", "radius", radius);
  require_positive("sphere_mesh", "max_edge", max_edge);
  // The icosahedron, its faces counter-clockwise seen from outside.
  const double p = std::numbers::phi;
  TriangleMesh unit{{{-1, p, 0}, {1, p, 0}, {-1, -p, 0}, {1, -p, 0}, {0, -1, p}, {0, 1, p},
                     {0, -1, -p}, {0, 1, -p}, {p, 0, -1}, {p, 0, 1}, {-p, 0, -1}, {-p, 0, 1}},
                    {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                     {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
                     {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}}};
  for (auto& v : unit.vertices) v = mul(1 / norm(v), v);
  constexpr std::size_t kMaxTriangles = 20 * 1024;  // five subdivisions
  while (unit.triangles.size() < kMaxTriangles && radius * longest_edge(unit) > max_edge) unit = subdivide(unit);
  for (auto& v : unit.vertices) v = add(center, mul(radius, v));
  return unit;
}

TriangleMesh cylinder_mesh(const Vec& base, const Vec& top, double radius, double max_edge) {
  require_positive("cylinder_mesh", "radius", radius);
  require_positive("cylinder_mesh", "max_edge", max_edge);
  const Vec axis = sub(top, base);
  require_positive("cylinder_mesh", "the distance from base to top", norm(axis));
  const auto [e1, e2] = frame_around(mul(1 / norm(axis), axis));
  // Rim edges of length 2 r sin(pi / n) <= 2 pi r / n.
  const double wanted = std::ceil(2 * std::numbers::pi * radius / max_edge);
  const auto n = static_cast<std::uint32_t>(std::clamp(wanted, 16.0, 1024.0));
  // Vertices: the base rim 0..n-1, the top rim n..2n-1, the base centre 2n, the top centre 2n+1.
  TriangleMesh m;
  for (const Vec& centre : {base, top})
    for (std::uint32_t k = 0; k < n; ++k) {
      const double a = 2 * std::numbers::pi * k / n;
      m.vertices.push_back(add(centre, add(mul(radius * std::cos(a), e1), mul(radius * std::sin(a), e2))));
    }
  m.vertices.push_back(base);
  m.vertices.push_back(top);
  // The angle grows counter-clockwise seen from the top, so these face out.
  for (std::uint32_t k = 0; k < n; ++k) {
    const std::uint32_t next = (k + 1) % n;
    m.triangles.insert(m.triangles.end(), {{k, next, n + next}, {k, n + next, n + k}});
    m.triangles.push_back({2 * n, next, k});              // base cap, facing -axis
    m.triangles.push_back({2 * n + 1, n + k, n + next});  // top cap, facing +axis
  }
  return m;
}

TriangleMesh plane_patch(const Vec& point, const Vec& normal, const Vec& lo, const Vec& hi) {
  require_box("plane_patch", lo, hi);
  require_positive("plane_patch", "the length of the normal", norm(normal));
  const Vec n = mul(1 / norm(normal), normal);
  // The polygon's corners are where the box's edges cross the plane: corners of the box on
  // the plane, and points inside edges whose ends lie on opposite sides.
  Vec corner[8];
  double side[8];
  for (int i = 0; i < 8; ++i) {
    corner[i] = {i & 1 ? hi[0] : lo[0], i & 2 ? hi[1] : lo[1], i & 4 ? hi[2] : lo[2]};
    side[i] = dot(sub(corner[i], point), n);
  }
  std::vector<Vec> points;
  for (int i = 0; i < 8; ++i)
    if (side[i] == 0) points.push_back(corner[i]);
  for (int i = 0; i < 8; ++i)
    for (int bit = 1; bit < 8; bit <<= 1) {
      const int j = i | bit;
      if (j == i || !((side[i] < 0 && side[j] > 0) || (side[i] > 0 && side[j] < 0))) continue;
      const double t = side[i] / (side[i] - side[j]);
      points.push_back(add(corner[i], mul(t, sub(corner[j], corner[i]))));
    }
  TriangleMesh m;
  if (points.size() < 3) return m;
  // The polygon is convex: order its corners by angle about their mean, counter-clockwise
  // seen from the side `normal` points to.
  const auto frame = frame_around(n);  // not a structured binding: clang 14 cannot capture one
  const Vec u = frame.first, v = frame.second;
  Vec mean{0, 0, 0};
  for (const Vec& p : points) mean = add(mean, mul(1.0 / points.size(), p));
  auto angle = [&](const Vec& p) { return std::atan2(dot(sub(p, mean), v), dot(sub(p, mean), u)); };
  std::sort(points.begin(), points.end(), [&](const Vec& a, const Vec& b) { return angle(a) < angle(b); });
  m.vertices = points;
  for (std::uint32_t k = 1; k + 1 < points.size(); ++k) {
    // A plane through an edge or a corner only touches the box: no area, nothing to draw.
    if (norm(cross(sub(points[k], points[0]), sub(points[k + 1], points[0]))) > 0) m.triangles.push_back({0, k, k + 1});
  }
  if (m.triangles.empty()) m.vertices.clear();
  return m;
}

}  // namespace pbf
