#include "engine/render/solid_raster.hpp"

#include <algorithm>
#include <cmath>

namespace pbf::render {

namespace {

constexpr double kGuardBand = 4;  // pixels the clipped view reaches beyond the scene area

// A plane of camera space, f(p) = n.p + d; the side f >= 0 is kept.
struct Plane {
  Vec3 n;
  double d;
  double operator()(const Vec3& p) const { return dot(n, p) + d; }
};

// Sutherland-Hodgman: the part of the convex polygon in[0..count) on the kept side, into out
// (room for count + 1 corners); returns its corner count. A crossing edge's new corner is
// interpolated from its inside end, so the two triangles sharing an edge get the same point.
int clip(const Vec3* in, int count, const Plane& plane, Vec3* out) {
  int kept = 0;
  for (int k = 0; k < count; ++k) {
    const Vec3 &p = in[k], &q = in[(k + 1) % count];
    const double fp = plane(p), fq = plane(q);
    if (fp >= 0) out[kept++] = p;
    if ((fp >= 0) != (fq >= 0)) {
      const Vec3 &inside = fp >= 0 ? p : q, &outside = fp >= 0 ? q : p;
      const double f_in = fp >= 0 ? fp : fq, f_out = fp >= 0 ? fq : fp;
      const double s = f_in / (f_in - f_out);
      out[kept++] = {inside[0] + s * (outside[0] - inside[0]), inside[1] + s * (outside[1] - inside[1]),
                     inside[2] + s * (outside[2] - inside[2])};
    }
  }
  return kept;
}

// The colour of a water triangle whose normal, in camera axes, is n (facing the camera) and
// whose corner lies at `corner` (camera space): WaterShading's.
Rgb water_colour(const Vec3& n, const Vec3& corner) {
  const Vec3 toward_camera = unit(Vec3{-corner[0], -corner[1], -corner[2]});
  // Camera axes (x right, y up, z forward) to the light's (z toward the viewer).
  const Vec3 nl{n[0], n[1], -n[2]}, vl{toward_camera[0], toward_camera[1], -toward_camera[2]};
  const float* L = SphereShading::light;
  const double n_dot_l = std::max(0.0, nl[0] * L[0] + nl[1] * L[1] + nl[2] * L[2]);
  const double cos_view = std::clamp(dot(nl, vl), 0.0, 1.0);
  const double fresnel = WaterShading::f0 + (1 - WaterShading::f0) * std::pow(1 - cos_view, 5);
  const Vec3 h = unit(Vec3{L[0] + vl[0], L[1] + vl[1], L[2] + vl[2]});
  const double highlight = WaterShading::specular * std::pow(std::max(0.0, dot(nl, h)), 64);
  const double lit = SphereShading::ambient + SphereShading::diffuse * n_dot_l;
  Rgb rgb;
  for (int c = 0; c < 3; ++c) {
    const double v = (1 - fresnel) * WaterShading::body[c] * lit + fresnel * WaterShading::sky[c] + 255 * highlight;
    rgb[c] = static_cast<unsigned char>(std::clamp(v + 0.5, 0.0, 255.0));
  }
  return rgb;
}

ScreenPolygon project_triangle(const Camera& cam, const SolidSurface& surface, std::size_t t, int width, int height) {
  ScreenPolygon poly;
  const TriangleMesh& mesh = *surface.mesh;
  const bool container = surface.container;
  const auto& tri = mesh.triangles[t];
  const Vec3 &v0 = mesh.vertices[tri[0]], &v1 = mesh.vertices[tri[1]], &v2 = mesh.vertices[tri[2]];
  // The outward normal and the side the camera sees: d > 0 when the normal points away.
  const Vec3 normal = cross(sub(v1, v0), sub(v2, v0));
  if (!finite(normal) || normal == Vec3{0, 0, 0}) return poly;
  const Vec3 n = unit(normal);
  const Vec3 nc{dot(n, cam.right), dot(n, cam.up), dot(n, cam.forward)};  // in camera axes
  Vec3 corners[2][ScreenPolygon::kMaxCorners + 1] = {{cam.to_camera(v0), cam.to_camera(v1), cam.to_camera(v2)}, {}};
  const double d = dot(nc, corners[0][0]);
  if (!std::isfinite(d) || d == 0 || (d > 0) != container) return poly;

  // Clip to the view: the near plane first (so that the side planes see positive depths).
  const double G = kGuardBand;
  const Plane planes[5] = {{{0, 0, 1}, -cam.near},
                           {{cam.focal, 0, cam.cx + G}, 0},
                           {{-cam.focal, 0, width + G - cam.cx}, 0},
                           {{0, -cam.focal, cam.cy + G}, 0},
                           {{0, cam.focal, height + G - cam.cy}, 0}};
  int count = 3, from = 0;
  for (const Plane& plane : planes) {
    for (int k = 0; k < count; ++k)
      if (!finite(corners[from][k])) return poly;
    count = clip(corners[from], count, plane, corners[1 - from]);
    from = 1 - from;
    if (count < 3) return poly;
  }

  double area = 0;
  for (int k = 0; k < count; ++k) {
    const Vec3& c = corners[from][k];
    poly.x[k] = static_cast<float>(cam.screen_x(c));
    poly.y[k] = static_cast<float>(cam.screen_y(c));
    if (!std::isfinite(poly.x[k]) || !std::isfinite(poly.y[k])) return poly;
  }
  for (int k = 0; k < count; ++k) {
    const int j = (k + 1) % count;
    area += double(poly.x[k]) * poly.y[j] - double(poly.x[j]) * poly.y[k];
  }
  if (!(area != 0) || !std::isfinite(area)) return poly;  // seen edge-on
  if (area < 0) {
    std::reverse(poly.x, poly.x + count);
    std::reverse(poly.y, poly.y + count);
  }

  // 1/depth along the ray through screen point (x, y) is (nc . ray) / d, ray = ((x - cx) / focal,
  // -(y - cy) / focal, 1) in camera axes: an affine function of x and y.
  poly.a = nc[0] / (cam.focal * d);
  poly.b = -nc[1] / (cam.focal * d);
  poly.c = nc[2] / d - poly.a * cam.cx - poly.b * cam.cy;
  if (!std::isfinite(poly.a) || !std::isfinite(poly.b) || !std::isfinite(poly.c)) return poly;

  if (surface.water) {  // the corners' normals toward the side seen (else the face's), for water_pixel
    const bool flip = dot(nc, corners[0][0]) > 0;
    poly.water = true;
    for (int k = 0; k < 3; ++k) {
      Vec3 shade = n;
      if (surface.normals) {
        const auto& m = (*surface.normals)[tri[k]];
        const Vec3 v{m[0], m[1], m[2]};
        if (finite(v) && !(v == Vec3{0, 0, 0})) shade = unit(v);
      }
      Vec3 sc{dot(shade, cam.right), dot(shade, cam.up), dot(shade, cam.forward)};
      if (flip) sc = {-sc[0], -sc[1], -sc[2]};
      for (int c = 0; c < 3; ++c) {
        poly.normal[k][c] = static_cast<float>(sc[c]);
        poly.corner[k][c] = static_cast<float>(corners[0][k][c]);
      }
    }
    poly.colour = water_colour(flip ? Vec3{-nc[0], -nc[1], -nc[2]} : nc, corners[0][0]);
  } else {
  // Flat Lambert shading with the normal of the side seen, in the light's axes (z toward the viewer).
  const double toward = d > 0 ? -1 : 1;
  const float* L = SphereShading::light;
  const float lambert = std::max(0.0f, static_cast<float>(toward * (L[0] * nc[0] + L[1] * nc[1] - L[2] * nc[2])));
  const float lit = SolidShading::grey * (SphereShading::ambient + SphereShading::diffuse * lambert);
  const auto grey = static_cast<unsigned char>(std::min(255.0f, lit + 0.5f));
  poly.colour = {grey, grey, grey};
  }

  poly.x_lo = *std::min_element(poly.x, poly.x + count), poly.x_hi = *std::max_element(poly.x, poly.x + count);
  poly.y_lo = *std::min_element(poly.y, poly.y + count), poly.y_hi = *std::max_element(poly.y, poly.y + count);
  poly.corners = count;
  return poly;
}

}  // namespace

std::vector<ScreenPolygon> project_solids(const Camera& cam, const std::vector<SolidSurface>& solids, int width,
                                          int height) {
  std::size_t total = 0;
  for (const auto& s : solids) total += s.mesh->triangles.size();
  std::vector<ScreenPolygon> polygons(total);
  std::size_t offset = 0;
  for (const auto& s : solids) {
    const std::size_t m = s.mesh->triangles.size();
#pragma omp parallel for schedule(static)
    for (std::size_t t = 0; t < m; ++t)
      polygons[offset + t] = project_triangle(cam, s, t, width, height);
    offset += m;
  }
  return polygons;
}

void rasterize(const ScreenPolygon& p, int x0, int y0, int x1, int y1, float* zbuf, std::uint32_t* owner,
               std::uint32_t id) {
  // The pixels whose centres (q + 0.5) may lie inside, within [x0, x1) x [y0, y1).
  auto first = [](float lo, int begin, int end) {
    return int(std::clamp(std::ceil(lo - 0.5f), float(begin), float(end)));
  };
  auto last = [](float hi, int begin, int end) {
    return int(std::clamp(std::floor(hi - 0.5f), float(begin - 1), float(end - 1)));
  };
  const int col0 = first(p.x_lo, x0, x1), col1 = last(p.x_hi, x0, x1);
  const int row0 = first(p.y_lo, y0, y1), row1 = last(p.y_hi, y0, y1);
  if (col0 > col1 || row0 > row1) return;

  // Each edge from its endpoint lower in (y, x), with the sign that makes the inside positive:
  // the neighbour across the edge evaluates the same expression with the other sign.
  struct Edge {
    double ax, ay, dx, dy, sign;
  } edges[ScreenPolygon::kMaxCorners];
  for (int k = 0; k < p.corners; ++k) {
    const int j = (k + 1) % p.corners;
    const bool swap = p.y[j] < p.y[k] || (p.y[j] == p.y[k] && p.x[j] < p.x[k]);
    const int a = swap ? j : k, b = swap ? k : j;
    edges[k] = {p.x[a], p.y[a], double(p.x[b]) - p.x[a], double(p.y[b]) - p.y[a], swap ? -1.0 : 1.0};
  }
  for (int py = row0; py <= row1; ++py) {
    const double qy = py + 0.5;
    for (int px = col0; px <= col1; ++px) {
      const double qx = px + 0.5;
      bool inside = true;
      for (int k = 0; k < p.corners && inside; ++k) {
        const Edge& e = edges[k];
        inside = e.sign * (e.dx * (qy - e.ay) - e.dy * (qx - e.ax)) >= 0;
      }
      if (!inside) continue;
      const double inverse_depth = p.a * qx + p.b * qy + p.c;
      if (!(inverse_depth > 0)) continue;
      const float depth = static_cast<float>(1 / inverse_depth);
      const int k = (py - y0) * kTile + (px - x0);
      if (depth < zbuf[k]) zbuf[k] = depth, owner[k] = id;
    }
  }
}

Rgb water_pixel(const ScreenPolygon& p, const Camera& cam, double qx, double qy) {
  // The point seen: on the ray through the pixel, at the polygon's depth there.
  const double inverse_depth = p.a * qx + p.b * qy + p.c;
  if (!(inverse_depth > 0)) return p.colour;
  const double z = 1 / inverse_depth;
  const Vec3 seen{(qx - cam.cx) / cam.focal * z, -(qy - cam.cy) / cam.focal * z, z};
  // Its barycentric weights in the triangle (clamped: a pixel centre on an edge of a clipped
  // polygon may lie a hair outside).
  const Vec3 a{p.corner[0][0], p.corner[0][1], p.corner[0][2]};
  const Vec3 e1 = sub(Vec3{p.corner[1][0], p.corner[1][1], p.corner[1][2]}, a);
  const Vec3 e2 = sub(Vec3{p.corner[2][0], p.corner[2][1], p.corner[2][2]}, a), e = sub(seen, a);
  const double d11 = dot(e1, e1), d12 = dot(e1, e2), d22 = dot(e2, e2), d1 = dot(e, e1), d2 = dot(e, e2);
  const double det = d11 * d22 - d12 * d12;
  if (!(det > 0)) return p.colour;
  double w[3] = {0, (d22 * d1 - d12 * d2) / det, (d11 * d2 - d12 * d1) / det};
  w[0] = 1 - w[1] - w[2];
  double total = 0;
  for (double& x : w) total += (x = std::clamp(x, 0.0, 1.0));
  Vec3 normal{0, 0, 0};
  for (int k = 0; k < 3; ++k)
    for (int c = 0; c < 3; ++c) normal[c] += w[k] / total * p.normal[k][c];
  if (!finite(normal) || normal == Vec3{0, 0, 0}) return p.colour;
  return water_colour(unit(normal), seen);
}

}  // namespace pbf::render
