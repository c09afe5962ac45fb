#include "engine/bodies/mass_properties.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <map>
#include <string>
#include <utility>

#include "engine/core/error.hpp"

namespace pbf {

namespace {

// Every edge once in each direction: a closed, consistently oriented surface.
void check_closed(const TriangleMesh& mesh, const std::string& what) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
  for (const auto& t : mesh.triangles)
    for (int e = 0; e < 3; ++e) ++edges[{t[e], t[(e + 1) % 3]}];
  for (const auto& [edge, count] : edges) {
    const auto back = edges.find({edge.second, edge.first});
    if (count != 1 || back == edges.end() || back->second != 1)
      throw Error(fmt::format("{}: the mesh is not closed (the edge between vertices {} and {} has {} triangle(s) "
                              "along it one way and {} the other): a body needs a closed surface to have a volume "
                              "and an inertia",
                              what, edge.first, edge.second, count, back == edges.end() ? 0 : back->second));
  }
}

}  // namespace

MassProperties mass_properties(const TriangleMesh& mesh, double density, const std::string& what) {
  if (!(density > 0 && std::isfinite(density)))
    throw Error(fmt::format("{}: the density must be positive and finite, not {}", what, density));
  check_closed(mesh, what);
  // The integrals about the bounding box's centre o, not the origin: a body far from the origin
  // would lose digits in C - m x_c x_c^T.
  std::array<double, 3> lo = mesh.vertices.at(0), hi = lo, o;
  for (const auto& v : mesh.vertices)
    for (int i = 0; i < 3; ++i) lo[i] = std::min(lo[i], v[i]), hi[i] = std::max(hi[i], v[i]);
  for (int i = 0; i < 3; ++i) o[i] = 0.5 * (lo[i] + hi[i]);
  auto from_o = [&](std::uint32_t k) {
    const auto& v = mesh.vertices[k];
    return std::array<double, 3>{v[0] - o[0], v[1] - o[1], v[2] - o[2]};
  };
  double volume = 0, first[3] = {0, 0, 0}, C[3][3] = {};
  for (const auto& t : mesh.triangles) {
    const auto a = from_o(t[0]), b = from_o(t[1]), c = from_o(t[2]);
    const double det = a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                       a[2] * (b[0] * c[1] - b[1] * c[0]);
    volume += det / 6;
    for (int i = 0; i < 3; ++i) first[i] += det / 24 * (a[i] + b[i] + c[i]);
    // det A C0 A^T: (A C0 A^T)_ij = (sum_k a_ik a_jk + (sum_k a_ik)(sum_k a_jk)) / 120 over the
    // columns a, b, c.
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        C[i][j] += det / 120 * (a[i] * a[j] + b[i] * b[j] + c[i] * c[j] + (a[i] + b[i] + c[i]) * (a[j] + b[j] + c[j]));
  }
  if (!(volume > 0))
    throw Error(fmt::format("{}: the mesh encloses a volume of {} m^3: its triangles must face outward (counter-"
                            "clockwise seen from outside) around a solid of positive volume",
                            what, volume));
  MassProperties p;
  p.volume = volume;
  p.mass = density * volume;
  double from_o_center[3];
  for (int i = 0; i < 3; ++i) from_o_center[i] = first[i] / volume, p.center[i] = o[i] + from_o_center[i];
  double trace = 0;
  double Cc[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) Cc[i][j] = density * C[i][j] - p.mass * from_o_center[i] * from_o_center[j];
  for (int i = 0; i < 3; ++i) trace += Cc[i][i];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) p.inertia[i][j] = (i == j ? trace : 0) - Cc[i][j];
  return p;
}

void principal_axes(const Matrix3& tensor, std::array<double, 3>& moments, Matrix3& axes) {
  Matrix3 a = tensor, v{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  for (int sweep = 0; sweep < 50; ++sweep) {  // cyclic Jacobi: each rotation zeroes one off-diagonal pair
    const double off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
    const double scale = a[0][0] * a[0][0] + a[1][1] * a[1][1] + a[2][2] * a[2][2];
    if (off <= 1e-32 * scale) break;
    for (int p = 0; p < 2; ++p)
      for (int q = p + 1; q < 3; ++q) {
        if (a[p][q] == 0) continue;
        const double theta = (a[q][q] - a[p][p]) / (2 * a[p][q]);
        const double t = (theta >= 0 ? 1 : -1) / (std::fabs(theta) + std::sqrt(theta * theta + 1));
        const double c = 1 / std::sqrt(t * t + 1), s = t * c;
        for (int k = 0; k < 3; ++k) {  // a <- J^T a J, v <- v J
          const double akp = a[k][p], akq = a[k][q];
          a[k][p] = c * akp - s * akq;
          a[k][q] = s * akp + c * akq;
        }
        for (int k = 0; k < 3; ++k) {
          const double apk = a[p][k], aqk = a[q][k];
          a[p][k] = c * apk - s * aqk;
          a[q][k] = s * apk + c * aqk;
        }
        for (int k = 0; k < 3; ++k) {
          const double vkp = v[k][p], vkq = v[k][q];
          v[k][p] = c * vkp - s * vkq;
          v[k][q] = s * vkp + c * vkq;
        }
      }
  }
  int order[3] = {0, 1, 2};  // ascending moments
  std::sort(order, order + 3, [&](int i, int j) { return a[i][i] < a[j][j]; });
  for (int k = 0; k < 3; ++k) {
    moments[k] = a[order[k]][order[k]];
    for (int r = 0; r < 3; ++r) axes[r][k] = v[r][order[k]];
  }
  const double det = axes[0][0] * (axes[1][1] * axes[2][2] - axes[1][2] * axes[2][1]) -
                     axes[0][1] * (axes[1][0] * axes[2][2] - axes[1][2] * axes[2][0]) +
                     axes[0][2] * (axes[1][0] * axes[2][1] - axes[1][1] * axes[2][0]);
  if (det < 0)
    for (int r = 0; r < 3; ++r) axes[r][2] = -axes[r][2];  // right-handed
}

}  // namespace pbf
