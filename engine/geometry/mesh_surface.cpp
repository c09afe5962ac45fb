// Whether a mesh is closed, which way its triangles must face (a flood fill across shared
// edges, then each connected part's sign from the volume it encloses), and that volume
// (mesh_surface.hpp).
#include "engine/geometry/mesh_surface.hpp"

#include <algorithm>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>
#include <tuple>
#include <utility>
#include <vector>

#include "engine/core/error.hpp"
#include "engine/geometry/mesh_file.hpp"

namespace pbf {

namespace {

using Vec = std::array<double, 3>;
constexpr std::uint32_t kNone = ~std::uint32_t(0);
constexpr const char* kCounted = "counting the file's triangles from 1";

// One use of an edge by a triangle: the edge as (smaller, larger) vertex index, and whether
// the triangle runs along it from the smaller to the larger.
struct EdgeUse {
  std::uint32_t lo, hi, triangle;
  bool forward;
  bool operator<(const EdgeUse& o) const { return std::tie(lo, hi, triangle) < std::tie(o.lo, o.hi, o.triangle); }
  bool same_edge(const EdgeUse& o) const { return lo == o.lo && hi == o.hi; }
};

std::string point_text(const Vec& p) { return fmt::format("({:.6g}, {:.6g}, {:.6g})", p[0], p[1], p[2]); }

std::string edge_text(const TriangleMesh& mesh, const EdgeUse& e) {
  return fmt::format("the edge from {} to {}", point_text(mesh.vertices[e.lo]), point_text(mesh.vertices[e.hi]));
}

std::string corners_text(const TriangleMesh& mesh, std::uint32_t t) {
  const auto& c = mesh.triangles[t];
  return fmt::format("{}, {}, {}", point_text(mesh.vertices[c[0]]), point_text(mesh.vertices[c[1]]),
                     point_text(mesh.vertices[c[2]]));
}

// Six times the signed volume of the tetrahedron from `c` to triangle t.
double six_volume(const TriangleMesh& mesh, const std::array<std::uint32_t, 3>& t, const Vec& c) {
  Vec p[3];
  for (int k = 0; k < 3; ++k)
    for (int d = 0; d < 3; ++d) p[k][d] = mesh.vertices[t[k]][d] - c[d];
  return p[0][0] * (p[1][1] * p[2][2] - p[1][2] * p[2][1]) - p[0][1] * (p[1][0] * p[2][2] - p[1][2] * p[2][0]) +
         p[0][2] * (p[1][0] * p[2][1] - p[1][1] * p[2][0]);
}

// The centre of the mesh's bounds: volumes about it cancel less than about a far origin.
Vec centre(const TriangleMesh& mesh) {
  const auto [lo, hi] = bounds(mesh);
  return {(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2};
}

// Every triangle's three edges, sorted so that the uses of one edge are together.
std::vector<EdgeUse> edge_uses(const TriangleMesh& mesh, const std::string& what) {
  std::vector<EdgeUse> uses;
  uses.reserve(3 * mesh.triangles.size());
  for (std::uint32_t i = 0; i < mesh.triangles.size(); ++i) {
    const auto& t = mesh.triangles[i];
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = t[k], b = t[(k + 1) % 3];
      if (std::max(a, b) >= mesh.vertices.size())
        throw Error(fmt::format("{}: triangle {} refers to vertex {}, but there are {} vertices", what, i + 1,
                                std::max(a, b) + 1, mesh.vertices.size()));
      uses.push_back({std::min(a, b), std::max(a, b), i, a < b});
    }
  }
  std::sort(uses.begin(), uses.end());
  return uses;
}

// A closed surface that is a manifold has each edge on exactly two triangles.
void check_closed(const std::vector<EdgeUse>& uses, const TriangleMesh& mesh, const std::string& what) {
  std::size_t open = 0, crowded = 0;
  std::string example;
  for (std::size_t i = 0, j; i < uses.size(); i = j) {
    for (j = i + 1; j < uses.size() && uses[j].same_edge(uses[i]); ++j) {
    }
    if (j - i == 2) continue;
    ++(j - i == 1 ? open : crowded);
    if (example.empty())
      example = fmt::format("{} is {}", j - i == 1 ? "an open one" : "one with more than two triangles",
                            edge_text(mesh, uses[i]));
  }
  if (example.empty()) return;
  auto edges = [](std::size_t n) { return fmt::format("{} edge{}", n, n == 1 ? "" : "s"); };
  std::vector<std::string> counts;
  if (open) counts.push_back(fmt::format("{} open (on one triangle only)", edges(open)));
  if (crowded) counts.push_back(fmt::format("{} shared by more than two triangles", edges(crowded)));
  throw Error(fmt::format("{} is not a closed surface: {}; {}. A solid with fluid inside or outside it needs a "
                          "closed surface, to tell the two apart",
                          what, fmt::join(counts, ", "), example));
}

// The connected parts of a closed surface, and for each triangle whether it must turn to
// face as its part's first triangle does.
struct Parts {
  std::vector<std::uint32_t> of;  // the part of each triangle
  std::vector<char> turn;
  std::uint32_t count = 0;
};

// A flood fill across shared edges: two triangles that run along their shared edge the same
// way face opposite ways, so one of them must turn. Where that asks a triangle to turn and not
// to turn, the part is one-sided.
Parts join_parts(const std::vector<EdgeUse>& uses, const TriangleMesh& mesh, const std::string& what) {
  struct Neighbour {
    std::uint32_t triangle;
    std::uint32_t pair;  // the shared edge's two uses are at 2 pair and 2 pair + 1 in `uses`
    bool opposite;       // faces the opposite way
  };
  const std::size_t n = mesh.triangles.size();
  std::vector<std::array<Neighbour, 3>> neighbours(n);
  std::vector<std::uint8_t> found(n, 0);
  for (std::size_t i = 0; i < uses.size(); i += 2) {  // closed: the uses come in pairs
    const EdgeUse &a = uses[i], &b = uses[i + 1];
    const bool opposite = a.forward == b.forward;
    const auto pair = static_cast<std::uint32_t>(i / 2);
    neighbours[a.triangle][found[a.triangle]++] = {b.triangle, pair, opposite};
    neighbours[b.triangle][found[b.triangle]++] = {a.triangle, pair, opposite};
  }
  Parts parts{std::vector<std::uint32_t>(n, kNone), std::vector<char>(n, 0), 0};
  std::vector<std::uint32_t> stack;  // iterative: a large part may not overflow the stack
  for (std::uint32_t seed = 0; seed < n; ++seed) {
    if (parts.of[seed] != kNone) continue;
    parts.of[seed] = parts.count;
    stack.push_back(seed);
    while (!stack.empty()) {
      const std::uint32_t t = stack.back();
      stack.pop_back();
      for (const Neighbour& next : neighbours[t]) {
        const char turn = parts.turn[t] ^ char(next.opposite);
        if (parts.of[next.triangle] == kNone) {
          parts.of[next.triangle] = parts.count;
          parts.turn[next.triangle] = turn;
          stack.push_back(next.triangle);
        } else if (parts.turn[next.triangle] != turn) {
          throw Error(fmt::format(
              "{} is a one-sided surface, as a Moebius strip closed up: the triangles of the part that holds "
              "triangle {} ({}) cannot all face one way, so it has no inside; going round it, triangles {} and {} "
              "meet at {} facing opposite ways whichever way they are turned. A solid needs a surface with an "
              "inside: rebuild that part of the mesh",
              what, seed + 1, kCounted, t + 1, next.triangle + 1, edge_text(mesh, uses[2 * std::size_t(next.pair)])));
        }
      }
    }
    ++parts.count;
  }
  return parts;
}

// Refuses the triangles that face the wrong way, naming the first of the smaller set: turning
// those in the file leaves a surface that faces one way, outward or wholly inward (which is
// turned for the user).
[[noreturn]] void refuse_turned(const TriangleMesh& mesh, const Parts& parts, const std::string& what) {
  const std::size_t n = mesh.triangles.size();
  const std::size_t turned = static_cast<std::size_t>(std::count(parts.turn.begin(), parts.turn.end(), 1));
  const char wrong = turned <= n - turned ? 1 : 0;
  const auto first =
      static_cast<std::uint32_t>(std::find(parts.turn.begin(), parts.turn.end(), wrong) - parts.turn.begin());
  // Whether its whole part faces the wrong way (against the other parts, not its neighbours).
  bool whole_part = true;
  for (std::size_t t = 0; t < n && whole_part; ++t)
    whole_part = parts.of[t] != parts.of[first] || parts.turn[t] == wrong;
  throw Error(fmt::format(
      "{}: triangle {} ({}) faces the other way from {}; its corners are {}. {} of the {} triangles face so. "
      "Reverse the order of their corners in the file, or give orient = true (the default) to have them turned",
      what, first + 1, kCounted,
      whole_part ? "the rest of the surface, as does the whole separate part it belongs to"
                  : "the triangles around it",
      corners_text(mesh, first), wrong ? turned : n - turned, n));
}

}  // namespace

void orient_surface(TriangleMesh& mesh, const std::string& what, bool orient) {
  if (mesh.triangles.empty()) throw Error(fmt::format("{} has no triangles", what));
  const std::vector<EdgeUse> uses = edge_uses(mesh, what);
  check_closed(uses, mesh, what);
  Parts parts = join_parts(uses, mesh, what);

  // Each part faces the way in which it encloses a positive volume.
  const Vec c = centre(mesh);
  std::vector<double> volume(parts.count, 0);
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    volume[parts.of[t]] += (parts.turn[t] ? -1 : 1) * six_volume(mesh, mesh.triangles[t], c);
  std::size_t turned = 0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    parts.turn[t] ^= char(volume[parts.of[t]] < 0);
    turned += parts.turn[t];
  }

  if (turned == 0) return;
  // A surface wholly inside out is a convention of its file, not a mistake in it.
  if (turned < mesh.triangles.size()) {
    if (!orient) refuse_turned(mesh, parts, what);
    const auto first = std::find(parts.turn.begin(), parts.turn.end(), 1) - parts.turn.begin();
    spdlog::info("{}: turned {} of its {} triangles to face outward, as the rest of the surface does (the first, "
                 "triangle {}, {})",
                 what, turned, mesh.triangles.size(), first + 1, kCounted);
  }
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    if (parts.turn[t]) std::swap(mesh.triangles[t][1], mesh.triangles[t][2]);
}

double enclosed_volume(const TriangleMesh& mesh) {
  const Vec c = centre(mesh);  // the same volume for a closed surface as about the origin
  double six_v = 0;
  for (const auto& t : mesh.triangles) six_v += six_volume(mesh, t, c);
  return six_v / 6;
}

}  // namespace pbf
