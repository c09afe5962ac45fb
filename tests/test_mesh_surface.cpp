// Whether a mesh bounds a solid, and which way it faces (orient_surface): closed meshes pass
// unchanged; open and crowded edges and one-sided surfaces are refused; triangles that face
// the wrong way are named, or turned with `orient`, after which the solid's inside is right.
#include <gtest/gtest.h>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "engine/core/error.hpp"
#include "engine/geometry/mesh_file.hpp"
#include "engine/geometry/mesh_sdf.hpp"
#include "engine/geometry/mesh_surface.hpp"
#include "engine/geometry/primitives.hpp"
#include "test_util.hpp"

using namespace pbf;
using pbf::test::error_of;

namespace {

// The unit cube, outward, as an OBJ file of triangles read back: triangle k of the mesh is
// the file's face k.
TriangleMesh read_back(const TriangleMesh& m) {
  std::string obj;
  for (const auto& v : m.vertices) obj += fmt::format("v {} {} {}\n", v[0], v[1], v[2]);
  for (const auto& t : m.triangles) obj += fmt::format("f {} {} {}\n", t[0] + 1, t[1] + 1, t[2] + 1);
  return read_mesh_memory(obj.data(), obj.size(), "cube.obj", "obj");
}

TriangleMesh cube_with_triangle_11_reversed() {
  TriangleMesh m = box_mesh({0, 0, 0}, {1, 1, 1});
  std::swap(m.triangles[10][1], m.triangles[10][2]);
  return read_back(m);
}

// The engine's info lines, logged while it lives (the tests log warnings only).
struct InfoLevel {
  InfoLevel() { spdlog::set_level(spdlog::level::info); }
  ~InfoLevel() { spdlog::set_level(spdlog::level::warn); }
};

// Whether a second pass finds nothing to turn: every triangle faces outward.
bool faces_outward(const TriangleMesh& m) {
  TriangleMesh again = m;
  orient_surface(again, "again", false);
  return again.triangles == m.triangles;
}

}  // namespace

TEST(MeshSurface, AcceptsClosedMeshesUnchanged) {
  for (const TriangleMesh& m : {box_mesh({-1, 0, 2}, {0.5, 3, 2.25}), sphere_mesh({1, 2, 3}, 0.5, 0.05),
                                sphere_mesh({0, 0, 0}, 1, 10), cylinder_mesh({0, 0, 0}, {1, 1, 1}, 0.3, 0.01)}) {
    TriangleMesh copy = m;
    EXPECT_NO_THROW(orient_surface(copy, "primitive", false));
    EXPECT_EQ(copy.triangles, m.triangles);
  }
}

TEST(MeshSurface, RefusesOpenAndCrowdedEdges) {
  const TriangleMesh cube = box_mesh({0, 0, 0}, {1, 1, 1});
  for (bool orient : {false, true}) {
    TriangleMesh open = cube;
    open.triangles.resize(10);  // the +x face gone: its four sides are on one triangle each
    const std::string e = error_of([&] { orient_surface(open, "solid 'tank'", orient); });
    EXPECT_NE(e.find("solid 'tank' is not a closed surface: 4 edges open"), std::string::npos) << e;
    EXPECT_NE(e.find("needs a closed surface"), std::string::npos) << e;
    EXPECT_NE(e.find("the edge from ("), std::string::npos) << e;

    TriangleMesh fin = cube;
    fin.vertices.push_back({0.5, -1, 0});
    fin.triangles.push_back({0, 1, 8});  // a third triangle on the edge from (0, 0, 0) to (1, 0, 0)
    EXPECT_ERROR_NAMING(orient_surface(fin, "fin", orient), "fin", "1 edge shared by more than two triangles");
    EXPECT_ERROR_NAMING(orient_surface(fin, "fin", orient), "fin", "from (0, 0, 0) to (1, 0, 0)");
  }
}

// The projective plane on six vertices (the hemi-icosahedron): every edge on two triangles,
// and no way to make them agree across all of them.
TEST(MeshSurface, RefusesAOneSidedSurface) {
  TriangleMesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0.1}, {0.2, 1, 0.3}, {0.9, 0.8, 0.7}, {0.1, 0.4, 1}, {0.6, 0.1, 0.9}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}, {0, 5, 1},
                 {1, 2, 4}, {2, 3, 5}, {3, 4, 1}, {4, 5, 2}, {5, 1, 3}};
  for (bool orient : {false, true})
    EXPECT_ERROR_NAMING(orient_surface(m, "mesh file 'rp2.obj'", orient), "mesh file 'rp2.obj'",
                        "is a one-sided surface");
}

TEST(MeshSurface, NamesTheTriangleThatFacesTheWrongWay) {
  TriangleMesh m = cube_with_triangle_11_reversed();
  const auto& t = m.triangles[10];
  const auto corner = [&](int k) {
    const auto& v = m.vertices[t[k]];
    return fmt::format("({}, {}, {})", v[0], v[1], v[2]);
  };
  const std::string e = error_of([&] { orient_surface(m, "mesh file 'cube.obj'", false); });
  EXPECT_NE(e.find("mesh file 'cube.obj': triangle 11 (counting the file's triangles from 1) faces the other way "
                   "from the triangles around it; its corners are " +
                   corner(0) + ", " + corner(1) + ", " + corner(2) + ". 1 of the 12 triangles face so"),
            std::string::npos)
      << e;
  EXPECT_NE(e.find("Reverse the order of their corners in the file, or give orient = true"), std::string::npos) << e;

  // A cube turned inside out but for one triangle: that one is named.
  for (auto& tri : m.triangles) std::swap(tri[1], tri[2]);
  EXPECT_ERROR_NAMING(orient_surface(m, "cube.obj", false), "cube.obj", "triangle 11 (");
}

TEST(MeshSurface, TurnsTheTriangleThatFacesTheWrongWay) {
  TriangleMesh m = cube_with_triangle_11_reversed();
  const InfoLevel info;
  const test::LogCapture log;
  orient_surface(m, "mesh file 'cube.obj'", true);
  EXPECT_EQ(log.count("mesh file 'cube.obj': turned 1 of its 12 triangles to face outward"), 1) << log.text();
  EXPECT_NEAR(enclosed_volume(m), 1.0, 1e-12);
  EXPECT_TRUE(faces_outward(m));
  // The solid is the cube: inside at its centre, outside beside it.
  const auto shape = mesh_shape(m, 0.05, 0.2);
  EXPECT_LT(shape->signed_distance({0.5, 0.5, 0.5}), 0);
  EXPECT_NEAR(shape->signed_distance({0.5, 0.5, 0.9}), -0.1, 1e-3);
  EXPECT_NEAR(shape->signed_distance({1.1, 0.5, 0.5}), 0.1, 1e-3);
  EXPECT_GT(shape->signed_distance({1.5, 0.5, 0.5}), 0);
}

TEST(MeshSurface, TurnsAWhollyInsideOutMeshWithoutOrient) {
  TriangleMesh m = box_mesh({0, 0, 0}, {1, 1, 1});
  for (auto& t : m.triangles) std::swap(t[1], t[2]);
  const InfoLevel info;
  const test::LogCapture log;
  orient_surface(m, "cube", false);
  EXPECT_NEAR(enclosed_volume(m), 1.0, 1e-12);
  EXPECT_EQ(log.count("turned"), 0);  // a convention of the file, not a mistake
}

// Two cubes apart, the second inside out as a whole: each separate part faces outward.
TEST(MeshSurface, TurnsASeparatePartThatFacesInward) {
  TriangleMesh m = box_mesh({0, 0, 0}, {1, 1, 1});
  const TriangleMesh second = box_mesh({2, 0, 0}, {3, 1, 1});
  for (const auto& v : second.vertices) m.vertices.push_back(v);
  for (const auto& t : second.triangles) m.triangles.push_back({t[0] + 8, t[2] + 8, t[1] + 8});
  EXPECT_NEAR(enclosed_volume(m), 0.0, 1e-12);
  EXPECT_ERROR_NAMING(orient_surface(m, "two.obj", false), "two.obj",
                      "triangle 13 (counting the file's triangles from 1) faces the other way from the rest of the "
                      "surface, as does the whole separate part it belongs to");
  orient_surface(m, "two.obj", true);
  EXPECT_NEAR(enclosed_volume(m), 2.0, 1e-12);
  EXPECT_TRUE(faces_outward(m));
}
