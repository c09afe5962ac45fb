#include "engine/fixes/solid_shape.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <fstream>

#include "engine/core/error.hpp"
#include "engine/bodies/mass_properties.hpp"
#include "engine/geometry/mesh_file.hpp"
#include "engine/geometry/mesh_sdf.hpp"
#include "engine/geometry/mesh_surface.hpp"
#include "engine/geometry/primitives.hpp"

namespace pbf {

namespace {

double norm(const Point& v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

// FNV-1a of a file's bytes (0 when it cannot be read: the mesh reader then says why).
std::uint64_t hash_of_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::uint64_t hash = 14695981039346656037ull;
  char buffer[65536];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    for (std::streamsize k = 0; k < in.gcount(); ++k) hash = (hash ^ static_cast<unsigned char>(buffer[k])) * 1099511628211ull;
    if (!in) break;
  }
  return hash;
}

}  // namespace

SolidShape::SolidShape(const std::string& id, const Params& p) : id_(id), shape_name_(p.string("shape")) {
  const Vec3 scale = p.vec3("scale"), rotate = p.vec3("rotate"), translate = p.vec3("translate");
  for (int a = 0; a < 3; ++a) {
    placement_.scale[a] = scale[a];
    placement_.rotate_deg[a] = rotate[a];
    placement_.translate[a] = translate[a];
  }
  // Each shape's own parameters; another shape's given here is a slip, refused.
  const std::vector<std::pair<std::string, std::vector<std::string>>> own = {
      {"mesh", {"file", "orient"}},
      {"box", {"lo", "hi"}},
      {"sphere", {"center", "radius"}},
      {"cylinder", {"base", "top", "radius"}},
      {"plane", {"point", "normal"}}};
  for (const auto& [shape, names] : own)
    for (const auto& name : names) {
      bool used = false;
      for (const auto& [mine, my_names] : own)
        used = used || (mine == shape_name_ && std::find(my_names.begin(), my_names.end(), name) != my_names.end());
      if (!used && p.has(name))
        throw Error(fmt::format("parameter '{}' does not apply to shape '{}' (it belongs to '{}')", name, shape_name_,
                                shape));
    }
  auto need = [&](const char* name) {
    if (!p.has(name)) throw Error(fmt::format("shape '{}' needs the parameter '{}'", shape_name_, name));
    return p.vec3(name);
  };
  auto point = [](const Vec3& v) { return Point{v[0], v[1], v[2]}; };
  if (shape_name_ == "mesh") {
    if (!p.has("file")) throw Error("shape 'mesh' needs the parameter 'file' (an OBJ or STL file)");
    file_ = p.string("file");
    TriangleMesh mesh = read_mesh_file(file_);  // first: it refuses what is no mesh file (a device, a directory)
    file_hash_ = hash_of_file(file_);
    orient_surface(mesh, fmt::format("mesh file '{}'", file_), !p.has("orient") || p.boolean("orient"));
    place(mesh, placement_);
    surface_ = std::move(mesh);
    mesh_ = true;
    return;
  }
  if (shape_name_ == "box") {
    lo_ = point(need("lo"));
    hi_ = point(need("hi"));
    for (int a = 0; a < 3; ++a)
      if (!(hi_[a] > lo_[a])) throw Error(fmt::format("box: 'hi' must exceed 'lo' along {}", "xyz"[a]));
    surface_ = box_mesh(lo_, hi_);
  } else if (shape_name_ == "sphere" || shape_name_ == "cylinder") {
    if (!p.has("radius")) throw Error(fmt::format("shape '{}' needs the parameter 'radius'", shape_name_));
    radius_ = p.real("radius");
    if (shape_name_ == "sphere") {
      lo_ = point(need("center"));
      surface_ = sphere_mesh(lo_, radius_, radius_ / 8);
    } else {
      lo_ = point(need("base"));
      hi_ = point(need("top"));
      if (norm({hi_[0] - lo_[0], hi_[1] - lo_[1], hi_[2] - lo_[2]}) == 0)
        throw Error("cylinder: 'base' and 'top' are the same point");
      surface_ = cylinder_mesh(lo_, hi_, radius_, radius_ / 8);
    }
  } else {  // plane: its surface is drawn where it cuts the domain, known at the run
    lo_ = point(need("point"));
    hi_ = point(need("normal"));
    if (norm(hi_) == 0) throw Error("plane: 'normal' must not be zero");
    return;
  }
  place(surface_, placement_);
}

// A sphere's and a cylinder's second moment about the centre, C = integral of (x - c)(x - c)^T
// (per unit density), unplaced: the sphere's V r^2 / 5 on the diagonal, the cylinder's
// V (r^2 / 4 (1 - a a^T) + L^2 / 12 a a^T) along its axis a. The placement x -> A x + t (A its
// rotation times its scale) maps them as V' = |det A| V, c' = A c + t, C' = |det A| A C A^T,
// and the inertia is I = rho (trace(C') 1 - C').
MassProperties SolidShape::mass_properties(double density) const {
  const std::string what = fmt::format("solid '{}'", id_);
  if (is_plane()) throw Error(fmt::format("{}: a plane has no volume: it cannot be a body", what));
  if (mesh_ || shape_name_ == "box") return pbf::mass_properties(surface_, density, what);
  if (!(density > 0 && std::isfinite(density)))
    throw Error(fmt::format("{}: the density must be positive and finite, not {}", what, density));
  double volume, C[3][3] = {};
  Point center = lo_;
  if (shape_name_ == "sphere") {
    volume = 4 * M_PI / 3 * radius_ * radius_ * radius_;
    for (int i = 0; i < 3; ++i) C[i][i] = volume * radius_ * radius_ / 5;
  } else {
    const Point axis{hi_[0] - lo_[0], hi_[1] - lo_[1], hi_[2] - lo_[2]};
    const double L = norm(axis);
    volume = M_PI * radius_ * radius_ * L;
    for (int i = 0; i < 3; ++i) {
      center[i] = 0.5 * (lo_[i] + hi_[i]);
      for (int j = 0; j < 3; ++j) {
        const double aa = axis[i] * axis[j] / (L * L);
        C[i][j] = volume * (radius_ * radius_ / 4 * ((i == j) - aa) + L * L / 12 * aa);
      }
    }
  }
  const auto R = rotation_matrix(placement_.rotate_deg);
  double A[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) A[i][j] = R[3 * i + j] * placement_.scale[j];
  const double det = std::abs(A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) -
                              A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0]) +
                              A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]));
  MassProperties p;
  p.volume = det * volume;
  p.mass = density * p.volume;
  double placed[3][3] = {}, trace = 0;
  for (int i = 0; i < 3; ++i) {
    p.center[i] = placement_.translate[i];
    for (int j = 0; j < 3; ++j) p.center[i] += A[i][j] * center[j];
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l) placed[i][j] += det * A[i][k] * C[k][l] * A[j][l];
  }
  for (int i = 0; i < 3; ++i) trace += placed[i][i];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) p.inertia[i][j] = density * ((i == j) * trace - placed[i][j]);
  return p;
}

std::unique_ptr<Shape> SolidShape::make_shape(const Domain& dom, double cell, double reach) {
  if (mesh_) {
    check_against_domain(dom);
    return mesh_shape(surface_, cell, reach);
  }
  std::unique_ptr<Shape> shape = primitive(dom);
  check_against_domain(dom);
  return shape;
}

std::unique_ptr<Shape> SolidShape::primitive(const Domain& dom) {
  if (shape_name_ == "box") return box_shape(lo_, hi_, placement_);
  if (shape_name_ == "sphere") return sphere_shape(lo_, radius_, placement_);
  if (shape_name_ == "cylinder") return cylinder_shape(lo_, hi_, radius_, placement_);
  // A plane placed: its point and normal in the world, then an unplaced half-space.
  TriangleMesh marker;
  marker.vertices = {{lo_[0], lo_[1], lo_[2]}, {lo_[0] + hi_[0], lo_[1] + hi_[1], lo_[2] + hi_[2]}};
  place(marker, placement_);
  const Point at = marker.vertices[0];
  const Point normal{marker.vertices[1][0] - at[0], marker.vertices[1][1] - at[1], marker.vertices[1][2] - at[2]};
  surface_ = plane_patch(at, normal, {dom.lo[0], dom.lo[1], dom.lo[2]}, {dom.hi[0], dom.hi[1], dom.hi[2]});
  plane_point_ = at;
  plane_normal_ = normal;
  return plane_shape(at, normal, Placement{});
}

void SolidShape::check_against_domain(const Domain& dom) const {
  if (shape_name_ == "plane") {  // the half-space must reach into the domain
    bool touches = false;
    for (int k = 0; k < 8; ++k) {
      const Point corner{k & 1 ? dom.hi[0] : dom.lo[0], k & 2 ? dom.hi[1] : dom.lo[1], k & 4 ? dom.hi[2] : dom.lo[2]};
      touches = touches || (corner[0] - plane_point_[0]) * plane_normal_[0] + (corner[1] - plane_point_[1]) * plane_normal_[1] +
                                   (corner[2] - plane_point_[2]) * plane_normal_[2] <=
                               0;
    }
    if (!touches)
      throw Error(fmt::format("solid '{}' lies outside the domain: the plane through ({:.6g}, {:.6g}, {:.6g}) leaves "
                              "the whole domain on its fluid side",
                              id_, plane_point_[0], plane_point_[1], plane_point_[2]));
    return;
  }
  const auto b = bounds(surface_);
  for (int a = 0; a < 3; ++a)
    if (b[0][a] > dom.hi[a] || b[1][a] < dom.lo[a])
      throw Error(fmt::format("solid '{}' lies outside the domain: it spans [{:.6g}, {:.6g}] along {}, the domain "
                              "[{:.6g}, {:.6g}]",
                              id_, b[0][a], b[1][a], "xyz"[a], dom.lo[a], dom.hi[a]));
}

}  // namespace pbf
