// Triangle meshes: a cube read back from OBJ, ASCII STL and binary STL; placement against
// hand-computed vertices; the primitives' meshes against their exact volumes; and every
// malformed file refused with a pbf::Error naming it. Closedness and orientation:
// test_mesh_surface.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numbers>
#include <random>

#include "engine/core/error.hpp"
#include "engine/geometry/mesh_file.hpp"
#include "engine/geometry/mesh_surface.hpp"
#include "engine/geometry/primitives.hpp"
#include "test_util.hpp"

using namespace pbf;
using pbf::test::error_of;
namespace fs = std::filesystem;
using Vec = std::array<double, 3>;

namespace {


// The unit cube: corners i = x + 2y + 4z, faces counter-clockwise seen from outside.
const Vec kCorners[8] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}};
const int kQuads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};

std::string cube_obj() {
  std::string s = "# unit cube\no cube\n";
  for (const Vec& v : kCorners) s += fmt::format("v {} {} {}\n", v[0], v[1], v[2]);
  for (const auto& q : kQuads) s += fmt::format("f {} {} {} {}\n", q[0] + 1, q[1] + 1, q[2] + 1, q[3] + 1);
  return s;
}

std::vector<std::array<int, 3>> cube_triangles() {
  std::vector<std::array<int, 3>> t;
  for (const auto& q : kQuads) t.insert(t.end(), {{q[0], q[1], q[2]}, {q[0], q[2], q[3]}});
  return t;
}

std::string cube_ascii_stl() {
  std::string s = "solid cube\n";
  for (const auto& t : cube_triangles()) {
    s += " facet normal 0 0 0\n  outer loop\n";  // readers recompute zero normals
    for (int k : t) s += fmt::format("   vertex {} {} {}\n", kCorners[k][0], kCorners[k][1], kCorners[k][2]);
    s += "  endloop\n endfacet\n";
  }
  return s + "endsolid cube\n";
}

std::string cube_binary_stl() {
  std::string s(80, ' ');  // a header that does not start with "solid", as binary STLs must not
  const auto triangles = cube_triangles();
  auto put = [&](const void* p, std::size_t n) { s.append(static_cast<const char*>(p), n); };
  const auto count = static_cast<std::uint32_t>(triangles.size());
  put(&count, 4);  // little-endian, as the machines the tests run on
  for (const auto& t : triangles) {
    const float normal[3] = {0, 0, 0};
    put(normal, sizeof normal);
    for (int k : t)
      for (double x : kCorners[k]) {
        const auto f = static_cast<float>(x);
        put(&f, 4);
      }
    put("\0\0", 2);
  }
  return s;
}

void expect_unit_cube(const TriangleMesh& m) {
  EXPECT_EQ(m.triangles.size(), 12u);
  EXPECT_EQ(m.vertices.size(), 8u);  // joined by position: STL repeats them per triangle
  EXPECT_NEAR(enclosed_volume(m), 1.0, 1e-12);
  const auto [lo, hi] = bounds(m);
  EXPECT_EQ(lo, (Vec{0, 0, 0}));
  EXPECT_EQ(hi, (Vec{1, 1, 1}));
  TriangleMesh oriented = m;
  EXPECT_NO_THROW(orient_surface(oriented, "the cube", false));
  EXPECT_EQ(oriented.triangles, m.triangles);
}

// The cube as read from OBJ; its vertices are numbered as the triangles first use them.
TriangleMesh unit_cube() {
  const std::string obj = cube_obj();
  return read_mesh_memory(obj.data(), obj.size(), "cube.obj", "obj");
}

TriangleMesh read_text(const std::string& text, const std::string& hint = "obj") {
  return read_mesh_memory(text.data(), text.size(), "bad." + hint, hint);
}

void expect_near(const Vec& a, const Vec& b, double tol) {
  for (int d = 0; d < 3; ++d) EXPECT_NEAR(a[d], b[d], tol) << "component " << d;
}

}  // namespace

TEST(MeshFile, ReadsObjAsciiStlAndBinaryStl) {
  const test::TempDir dir("mesh");
  test::write_file(dir / "cube.obj", cube_obj());
  test::write_file(dir / "cube.stl", cube_ascii_stl());
  test::write_file(dir / "binary.STL", cube_binary_stl());  // the hint's case does not matter
  for (const char* name : {"cube.obj", "cube.stl", "binary.STL"}) {
    SCOPED_TRACE(name);
    expect_unit_cube(read_mesh_file((dir / name).string()));
  }
}

TEST(MeshFile, KeepsTheFilesOrientationAndJoinsMinusZero) {
  std::string obj = cube_obj();
  obj.replace(obj.find("v 0 0 0"), 7, "v -0 0 -0");
  TriangleMesh m = read_text(obj);
  EXPECT_EQ(m.vertices.size(), 8u);
  // An inward-facing file reads inward; orient_surface turns it, even without `orient`.
  for (auto& t : m.triangles) std::swap(t[0], t[1]);
  EXPECT_NEAR(enclosed_volume(m), -1.0, 1e-12);
  orient_surface(m, "the cube", false);
  EXPECT_NEAR(enclosed_volume(m), 1.0, 1e-12);
}

// glTF places meshes by a tree of nodes. The tetrahedron (0,0,0) (1,0,0) (0,1,0) (0,0,1),
// outward, is placed twice: mirrored in x (scale -1) under a parent moved by (5, 0, 2), so
// at x' = 5 - x, z' = z + 2; and moved by (0, 0, -5).
// Materials are not read: a missing library is no error, and (a crash of Assimp 5.2.5's
// ReadFileFromMemory, found by fuzz_mesh) the OBJ is not read again as its own library.
TEST(MeshFile, IgnoresMaterials) {
  expect_unit_cube(read_text("mtllib missing.mtl\nusemtl red\n" + cube_obj()));
  EXPECT_ERROR_NAMING(read_text("mtllib v \nmap_Kn"), "bad.obj", "no triangles");
  expect_unit_cube(read_text("mtllib x\nmap_Kd t.png\n" + cube_obj()));
}

// Assimp 5.2.5's OpenGEX reader reads past the end of a malformed file (found by fuzz_mesh,
// fuzz/corpus/mesh/regression_assimp_opengex_overread): it is never asked, even for a
// well-formed tetrahedron that it reads, nor when a file of another extension is offered to
// every reader.
TEST(MeshFile, NeverAsksTheOpenGexReader) {
  const std::string tetrahedron =
      "GeometryNode $node1 { ObjectRef {ref {$geometry1}} }\n"
      "GeometryObject $geometry1 { Mesh (primitive = \"triangles\") {\n"
      "  VertexArray (attrib = \"position\") { float[3] {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}} }\n"
      "  IndexArray { unsigned_int32[3] {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}} } } }\n";
  EXPECT_ERROR_NAMING(read_text(tetrahedron, "ogex"), "bad.ogex", "OpenGEX files are not read");
  EXPECT_ERROR_NAMING(read_text(tetrahedron, "txt"), "bad.txt", "not a mesh file that can be read");
  EXPECT_ERROR_NAMING(read_text(tetrahedron, ""), "bad.", "not a mesh file that can be read");
}

TEST(MeshFile, AppliesNodeTransformsAndUndoesMirroring) {
  const std::string gltf =
      R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0,2]}],)"
      R"("nodes":[{"translation":[5,0,2],"children":[1]},{"scale":[-1,1,1],"mesh":0},)"
      R"({"translation":[0,0,-5],"mesh":0}],"meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],)"
      R"("buffers":[{"byteLength":72,"uri":"data:application/octet-stream;base64,)"
      R"(AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAAAAAAAAAAAAIA/AAACAAEAAAABAAMAAAADAAIAAQACAAMA"}],)"
      R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":48},{"buffer":0,"byteOffset":48,"byteLength":24}],)"
      R"("accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","min":[0,0,0],"max":[1,1,1]},)"
      R"({"bufferView":1,"componentType":5123,"count":12,"type":"SCALAR"}]})";
  const TriangleMesh m = read_mesh_memory(gltf.data(), gltf.size(), "two.gltf", "gltf");
  EXPECT_EQ(m.triangles.size(), 8u);
  EXPECT_EQ(m.vertices.size(), 8u);
  for (const Vec& v : {Vec{5, 0, 2}, Vec{4, 0, 2}, Vec{5, 1, 2}, Vec{5, 0, 3}, Vec{0, 0, -5}, Vec{1, 0, -5},
                       Vec{0, 1, -5}, Vec{0, 0, -4}})
    EXPECT_NE(std::find(m.vertices.begin(), m.vertices.end(), v), m.vertices.end())
        << v[0] << " " << v[1] << " " << v[2];
  // Both copies face outward: the mirrored one's triangles were reversed.
  EXPECT_NEAR(enclosed_volume(m), 2.0 / 6, 1e-15);
  TriangleMesh oriented = m;
  EXPECT_NO_THROW(orient_surface(oriented, "two tetrahedra", false));
  EXPECT_EQ(oriented.triangles, m.triangles);
}

TEST(MeshPlace, ScalesRotatesThenTranslates) {
  // box_mesh numbers the corners as kCorners does.
  auto cube = [] { return box_mesh({0, 0, 0}, {1, 1, 1}); };
  TriangleMesh m = cube();
  place(m, Placement{{2, 2, 2}, {0, 0, 90}, {1, 2, 3}});
  // (1, 0, 0) -> scaled (2, 0, 0) -> a quarter turn about z (x, y) -> (-y, x): (0, 2, 0) -> + t.
  EXPECT_EQ(m.vertices[1], (Vec{1, 4, 3}));  // multiples of 90 degrees are exact
  // (0, 1, 1) -> (0, 2, 2) -> (-2, 0, 2) -> (-1, 2, 5).
  EXPECT_EQ(m.vertices[6], (Vec{-1, 2, 5}));
  EXPECT_NEAR(enclosed_volume(m), 8.0, 1e-12);

  // About x first, then y: Rx(90) (x, y, z) -> (x, -z, y); Ry(90) (x, y, z) -> (z, y, -x).
  // (1, 1, 1) -> (1, -1, 1) -> (1, -1, -1).
  m = cube();
  place(m, Placement{{1, 1, 1}, {90, 90, 0}, {0, 0, 0}});
  EXPECT_EQ(m.vertices[7], (Vec{1, -1, -1}));

  // 30 degrees about z: (1, 0, 0) -> (cos 30, sin 30, 0).
  m = cube();
  place(m, Placement{{1, 1, 1}, {0, 0, 30}, {0, 0, 0}});
  expect_near(m.vertices[1], {std::sqrt(3.0) / 2, 0.5, 0}, 1e-15);

  // A negative scale mirrors the cube through the origin but keeps it facing out.
  m = cube();
  place(m, Placement{{-1, -1, -1}, {0, 0, 0}, {0, 0, 0}});
  EXPECT_EQ(m.vertices[7], (Vec{-1, -1, -1}));
  EXPECT_NEAR(enclosed_volume(m), 1.0, 1e-12);
}

TEST(MeshPlace, RotationMatrixIsARotation) {
  const auto r = rotation_matrix({37, -120, 415});
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const double rrt = r[3 * i] * r[3 * j] + r[3 * i + 1] * r[3 * j + 1] + r[3 * i + 2] * r[3 * j + 2];
      EXPECT_NEAR(rrt, i == j ? 1 : 0, 1e-15);
    }
  const double det = r[0] * (r[4] * r[8] - r[5] * r[7]) - r[1] * (r[3] * r[8] - r[5] * r[6]) +
                     r[2] * (r[3] * r[7] - r[4] * r[6]);
  EXPECT_NEAR(det, 1, 1e-15);
  // R = Rz * Ry * Rx: its last row is (-sin y, sin x cos y, cos x cos y).
  const double x = 37 * std::numbers::pi / 180, y = -120 * std::numbers::pi / 180;
  EXPECT_NEAR(r[6], -std::sin(y), 1e-15);
  EXPECT_NEAR(r[7], std::sin(x) * std::cos(y), 1e-15);
  EXPECT_NEAR(r[8], std::cos(x) * std::cos(y), 1e-15);
}

TEST(MeshPrimitives, BoxVolumeAndBounds) {
  const TriangleMesh m = box_mesh({-1, 0, 2}, {0.5, 3, 2.25});
  EXPECT_EQ(m.triangles.size(), 12u);
  EXPECT_NEAR(enclosed_volume(m), 1.5 * 3 * 0.25, 1e-12);
  EXPECT_EQ(bounds(m)[0], (Vec{-1, 0, 2}));
  EXPECT_EQ(bounds(m)[1], (Vec{0.5, 3, 2.25}));
}

TEST(MeshPrimitives, SphereIsInscribedAndNearTheExactVolume) {
  const Vec c{1, 2, 3};
  const double r = 0.5, exact = 4.0 / 3 * std::numbers::pi * r * r * r;
  const TriangleMesh fine = sphere_mesh(c, r, 0.02);
  EXPECT_LE(fine.triangles.size(), 20480u);
  for (const Vec& v : fine.vertices) EXPECT_NEAR(std::hypot(v[0] - c[0], v[1] - c[1], v[2] - c[2]), r, 1e-14);
  // Inscribed: below the sphere's volume, by less than 1% at 20 480 triangles.
  const double v = enclosed_volume(fine);
  EXPECT_LT(v, exact);
  EXPECT_GT(v, 0.99 * exact);
  // Subdivided only as far as max_edge asks.
  const TriangleMesh coarse = sphere_mesh(c, r, 0.3);
  double longest = 0;
  for (const auto& t : coarse.triangles)
    for (int k = 0; k < 3; ++k) {
      const Vec &a = coarse.vertices[t[k]], &b = coarse.vertices[t[(k + 1) % 3]];
      longest = std::max(longest, std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]));
    }
  EXPECT_LE(longest, 0.3);
  EXPECT_LT(coarse.triangles.size(), fine.triangles.size());
  EXPECT_EQ(sphere_mesh(c, r, 1e-9).triangles.size(), 20480u);  // the cap
}

TEST(MeshPrimitives, CylinderIsTheInscribedPrism) {
  const Vec base{0.1, 0.2, 0.3}, top{1.1, 1.2, 1.3};
  const double r = 0.2, h = std::sqrt(3.0);
  const TriangleMesh m = cylinder_mesh(base, top, r, 0.01);
  const std::size_t n = (m.vertices.size() - 2) / 2;
  EXPECT_EQ(n, 126u);  // ceil(2 pi 0.2 / 0.01)
  EXPECT_EQ(m.triangles.size(), 4 * n);
  // The prism on the inscribed regular n-gon, exactly; within 1% of the cylinder.
  const double prism = n / 2.0 * r * r * std::sin(2 * std::numbers::pi / n) * h;
  EXPECT_NEAR(enclosed_volume(m), prism, 1e-12 * prism);
  EXPECT_GT(prism, 0.99 * std::numbers::pi * r * r * h);
  EXPECT_EQ(cylinder_mesh(base, top, r, 10).vertices.size(), 2 * 16 + 2u);
  EXPECT_EQ(cylinder_mesh(base, top, r, 1e-9).vertices.size(), 2 * 1024 + 2u);
  EXPECT_ERROR_NAMING(cylinder_mesh(base, base, r, 0.1), "cylinder_mesh", "distance from base to top");
  EXPECT_ERROR_NAMING(sphere_mesh(base, -1, 0.1), "sphere_mesh", "radius");
}

TEST(MeshPrimitives, PlanePatchIsTheSectionOfTheBox) {
  auto area_along = [](const TriangleMesh& m, const Vec& n) {
    double a = 0;  // the projection of each triangle's area vector on n: its area if it faces along n
    for (const auto& t : m.triangles) {
      const Vec &p = m.vertices[t[0]], &q = m.vertices[t[1]], &s = m.vertices[t[2]];
      const Vec u{q[0] - p[0], q[1] - p[1], q[2] - p[2]}, v{s[0] - p[0], s[1] - p[1], s[2] - p[2]};
      const Vec c{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
      const double cn = (c[0] * n[0] + c[1] * n[1] + c[2] * n[2]) / 2;
      EXPECT_GT(cn, 0) << "a triangle faces away from the normal";
      a += cn;
    }
    return a;
  };
  const TriangleMesh square = plane_patch({0, 0, 0.25}, {0, 0, -3}, {0, 0, 0}, {2, 1, 1});
  EXPECT_EQ(square.vertices.size(), 4u);
  EXPECT_NEAR(area_along(square, {0, 0, -1}), 2.0, 1e-12);
  // Through the cube's centre, normal to its diagonal: the regular hexagon of side 1/sqrt(2).
  const double s3 = 1 / std::sqrt(3.0);
  const TriangleMesh hexagon = plane_patch({0.5, 0.5, 0.5}, {1, 1, 1}, {0, 0, 0}, {1, 1, 1});
  EXPECT_EQ(hexagon.vertices.size(), 6u);
  EXPECT_NEAR(area_along(hexagon, {s3, s3, s3}), 3 * std::sqrt(3.0) / 4, 1e-12);
  EXPECT_TRUE(plane_patch({0, 0, 2}, {0, 0, 1}, {0, 0, 0}, {1, 1, 1}).triangles.empty());  // misses
  EXPECT_TRUE(plane_patch({0, 0, 0}, {1, 1, 1}, {0, 0, 0}, {1, 1, 1}).triangles.empty());  // a corner
  EXPECT_TRUE(plane_patch({0, 0, 0}, {1, 1, 0}, {0, 0, 0}, {1, 1, 1}).triangles.empty());  // an edge
}

TEST(MeshFile, RefusesMissingAndEmptyFiles) {
  const test::TempDir dir("mesh-refused");
  const std::string missing = (dir / "missing.obj").string();
  EXPECT_ERROR_NAMING(read_mesh_file(missing), "mesh file '" + missing + "'", "not found");
  // A relative path: the message says where it was looked for.
  EXPECT_ERROR_NAMING(read_mesh_file("no-such-mesh.obj"), "mesh file 'no-such-mesh.obj' not found",
                      ": relative paths are taken from the current folder, " + fs::current_path().string());
  EXPECT_ERROR_NAMING(read_mesh_file(dir.string()), dir.string(), "cannot be read (it is a directory)");
  test::write_file(dir / "empty.stl", "");
  EXPECT_ERROR_NAMING(read_mesh_file((dir / "empty.stl").string()), "empty.stl", "the file is empty");
  EXPECT_ERROR_NAMING(read_mesh_memory("", 0, "nothing.obj", "obj"), "nothing.obj", "empty");
}

TEST(MeshFile, RefusesWhatIsNotAMesh) {
  std::string garbage;
  std::mt19937 rng(7);
  for (int i = 0; i < 300; ++i) garbage += static_cast<char>(rng());
  // Assimp's OBJ reader takes anything and finds no faces; its STL reader finds no format.
  EXPECT_ERROR_NAMING(read_text(garbage, "obj"), "bad.obj", "no triangles");
  EXPECT_ERROR_NAMING(read_text(garbage, "stl"), "bad.stl", "not a mesh file that can be read");
  EXPECT_ERROR_NAMING(read_text(garbage, ""), "bad.", "not a mesh file that can be read");
  const std::string stl = cube_binary_stl();
  EXPECT_ERROR_NAMING(read_text(stl.substr(0, 200), "stl"), "bad.stl", "not a mesh file that can be read");
  EXPECT_ERROR_NAMING(read_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\n"), "bad.obj", "no triangles");
}

TEST(MeshFile, RefusesBadNumbersAndIndices) {
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  EXPECT_ERROR_NAMING(read_text("v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"), "bad.obj",
                    "triangle 1 has a vertex coordinate that is not a finite number (nan)");
  EXPECT_ERROR_NAMING(read_text("v 1e39 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"), "bad.obj", "not a finite number (inf)");
  EXPECT_ERROR_NAMING(read_text(tri + "v 2e6 0 0\nf 1 2 3\nf 2 4 3\n"), "bad.obj",
                    "triangle 2 has a vertex coordinate of 2e+06 m");
  EXPECT_ERROR_NAMING(read_text(tri + "f 1 2 99\n"), "bad.obj", "index out of range");
  EXPECT_ERROR_NAMING(read_text(tri + "f 1 2 -5\n"), "bad.obj", "not a mesh file that can be read");
  // Degenerate: a repeated corner, and three corners on a line.
  EXPECT_ERROR_NAMING(read_text(tri + "v 2 0 0\nf 1 2 3\nf 1 2 2\nf 1 2 4\n"), "bad.obj",
                    "triangle 2 has no area (two of its corners coincide or all three lie on a line); 2 of the 3");
  EXPECT_ERROR_NAMING(read_text(tri + "v 0 0 0\nf 1 2 3\nf 4 2 1\n"), "bad.obj", "triangle 2 has no area");
}
