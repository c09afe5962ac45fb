// dump/surface in runs: a settled column's mesh, the dam break's meshes at every frame
// (splashes included) closed and manifold and the same bytes at one and two threads, the
// formats written, a restart that continues the collection, and bad parameters refused.
#include <cmath>
#include <cstring>
#include <fstream>
#include <numbers>

#include <gtest/gtest.h>

#include "tests/surface_checks.hpp"
#include "tests/test_util.hpp"

namespace pbf {
namespace {

using namespace surface_checks;
using test::read_file;
using test::run_engine;
using test::scenario;

// A binary PLY as dump/surface writes it: float x y z nx ny nz and more float properties per
// vertex, then faces as uchar-counted int lists.
struct Ply {
  TriangleMesh mesh;
  std::vector<std::array<float, 3>> normals;
  std::vector<std::string> properties;
  std::vector<std::vector<float>> values;  // per vertex, every property
};

Ply read_ply(const std::filesystem::path& path) {
  const std::string bytes = read_file(path);
  Ply ply;
  const std::size_t end = bytes.find("end_header\n");
  if (end == std::string::npos) throw std::runtime_error(path.string() + ": no PLY header");
  std::istringstream head(bytes.substr(0, end));
  std::string line;
  std::size_t vertices = 0, faces = 0;
  while (std::getline(head, line)) {
    std::istringstream w(line);
    std::string word, kind, type, name;
    w >> word;
    if (word == "element") {
      w >> kind;
      (kind == "vertex" ? vertices : faces) = std::stoul(w.str().substr(w.str().rfind(' ') + 1));
    } else if (word == "property") {
      w >> type >> name;
      if (type == "float") ply.properties.push_back(name);
    }
  }
  const std::size_t columns = ply.properties.size();
  const char* at = bytes.data() + end + std::strlen("end_header\n");
  for (std::size_t v = 0; v < vertices; ++v) {
    std::vector<float> row(columns);
    std::memcpy(row.data(), at, columns * 4);
    at += columns * 4;
    ply.mesh.vertices.push_back({row[0], row[1], row[2]});
    ply.normals.push_back({row[3], row[4], row[5]});
    ply.values.push_back(row);
  }
  for (std::size_t f = 0; f < faces; ++f) {
    if (*at != 3) throw std::runtime_error(path.string() + ": a face that is not a triangle");
    std::int32_t idx[3];
    std::memcpy(idx, at + 1, 12);
    at += 13;
    ply.mesh.triangles.push_back({std::uint32_t(idx[0]), std::uint32_t(idx[1]), std::uint32_t(idx[2])});
  }
  if (at != bytes.data() + bytes.size()) throw std::runtime_error(path.string() + ": bytes left after the faces");
  return ply;
}

// Connected pieces of a mesh (union-find over its triangles' vertices).
std::size_t pieces(const TriangleMesh& m) {
  std::vector<std::uint32_t> parent(m.vertices.size());
  for (std::uint32_t v = 0; v < parent.size(); ++v) parent[v] = v;
  auto find = [&](std::uint32_t v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for (const auto& t : m.triangles) parent[find(t[1])] = find(t[0]), parent[find(t[2])] = find(t[0]);
  std::size_t roots = 0;
  for (std::uint32_t v = 0; v < parent.size(); ++v) roots += find(v) == v;
  return roots;
}

TEST(DumpSurface, RestingColumnEnclosesItsVolumeWithAFlatTopAtItsHeightAndStaysSoWhenSettled) {
  auto dir = test::temp_dir("surface-column");
  // 10 x 10 x 20 particles at 1 cm in a box: meshed as placed (at rest on the lattice) and after
  // half a second under DFSPH (which holds a column at its rest density, 0.04% compressed, and nearly
  // still: docs/validation/dfsph.md), with text frames of the particles beside.
  test::write_file(dir / "column.lua", R"(
    local s = 0.01
    pbf.domain{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.3}}
    pbf.kernel_radius(2 * s)
    pbf.timestep(0.4 * 2 * s / math.sqrt(2 * 9.81 * 0.2))
    pbf.lattice{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.2}, spacing = s}
    pbf.fix("gravity", "gravity", {})
    pbf.fix("dfsph", "dfsph", {})
    pbf.fix("viscosity", "sph_viscosity", {kind = "laplacian", nu = 1e-3})
    pbf.fix("walls", "box", {})
    pbf.fix("surface", "dump/surface", {path = var.OUT .. "/surface_*.ply", fields = {"velocity", "density"}, interval = 0.5})
    pbf.fix("frames", "dump/text", {path = var.OUT .. "/frame_*.txt", interval = 0.5})
    pbf.run_until(0.5)
  )");
  const auto r = run_engine("run " + (dir / "column.lua").string() + " -v OUT=" + dir.string());
  ASSERT_EQ(r.code, 0) << r.output;
  const double s = 0.01, particles = 10 * 10 * 20, lattice_volume = particles * s * s * s;
  for (int frame : {0, 1}) {
    SCOPED_TRACE(frame == 0 ? "as placed" : "settled");
    const Ply ply = read_ply(dir / fmt::format("surface_{:05d}.ply", frame));
    EXPECT_EQ(manifold_defect(ply.mesh), "");
    EXPECT_EQ(pieces(ply.mesh), 1u);
    EXPECT_EQ(self_intersections(ply.mesh, s), 0u);
    EXPECT_NEAR(enclosed_volume(ply.mesh) / lattice_volume, 1, 0.02);
    // The top, more than 2 s from the walls: its height against the particles' top layer's
    // (half a spacing below the water's surface), and its slope.
    auto away_from_walls = [&](double x, double y) { return x > 2 * s && x < 0.1 - 2 * s && y > 2 * s && y < 0.1 - 2 * s; };
    const auto rows = test::read_frame_rows(dir / fmt::format("frame_{:05d}.txt", frame));
    double highest = 0, layer = 0, count = 0;
    for (const auto& row : rows)
      if (away_from_walls(row[0], row[1])) highest = std::max(highest, row[2]);
    for (const auto& row : rows)
      if (row[2] > highest - s / 2 && away_from_walls(row[0], row[1])) layer += row[2], count += 1;
    ASSERT_GT(count, 0);
    const double height = layer / count + s / 2;
    double worst_angle = 0, mean_height = 0, top = 0;
    for (std::size_t v = 0; v < ply.mesh.vertices.size(); ++v) {
      const auto& x = ply.mesh.vertices[v];
      if (x[2] < height - 2 * s || !away_from_walls(x[0], x[1])) continue;
      worst_angle = std::max(worst_angle, std::acos(std::min(1.0f, ply.normals[v][2])) * 180 / std::numbers::pi);
      mean_height += x[2], top += 1;
    }
    mean_height /= top;
    EXPECT_NEAR(mean_height, height, s / 4);
    if (frame == 0) {  // on the lattice: the column's height exactly, and flat
      EXPECT_NEAR(height, 0.2, 1e-6);
      EXPECT_LT(worst_angle, 5.0);
    }
    // The fields ride on the vertices: velocity's three components (the column is at rest, then
    // nearly: a few cm/s) and density, the rest density's where the kernels are full (below the
    // top layers).
    ASSERT_EQ(ply.properties.size(), 6u + 3 + 1);
    EXPECT_EQ(ply.properties[6], "velocity_x");
    EXPECT_EQ(ply.properties[9], "density");
    for (const auto& row : ply.values) {
      EXPECT_LT(std::hypot(row[6], row[7], row[8]), frame == 0 ? 1e-9 : 0.1);
      if (row[2] < 0.15) EXPECT_NEAR(row[9], 1000, 20);
    }
  }
}

// The dam break at 8,000 particles, a surface every 0.1 s to 0.6 s: the surge has hit the far
// wall and thrown up a splash of small pieces by then.
test::SplitRun dam_break_surfaces(const std::filesystem::path& dir, int threads) {
  return test::run_in(dir,
                      "run " + scenario("dambreak.lua") + " -v particles=8000 -v t_end=0.6 -v out=out -v surface=0.1 "
                      "-v restart_interval=0 -v interval=1 --log none",
                      "OMP_NUM_THREADS=" + std::to_string(threads));
}

TEST(DumpSurface, AColumnInAMeshTankMeetsItsWallsSquareWithTheFluidMirroredAcrossThem) {
  auto dir = test::temp_dir("surface-mesh-tank");
  // The column of the test above, 10 x 10 x 20 particles at 1 cm, in a `solid` box tank
  // (fluid inside) that stands 5 cm inside the domain's walls on every side: only the solid's
  // faces touch the water. Meshed as placed, with the solids mirrored and without.
  test::write_file(dir / "tank.lua", R"(
    local s = 0.01
    pbf.domain{lo = {-0.05, -0.05, -0.05}, hi = {0.15, 0.15, 0.35}}
    pbf.kernel_radius(2 * s)
    pbf.timestep(1e-3)
    pbf.lattice{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.2}, spacing = s}
    pbf.fix("tank", "solid", {shape = "box", lo = {0, 0, 0}, hi = {0.1, 0.1, 0.3}, fluid = "inside"})
    pbf.fix("mirrored", "dump/surface", {path = var.OUT .. "/mirrored_*.ply", interval = 1})
    pbf.fix("plain", "dump/surface", {path = var.OUT .. "/plain_*.ply", interval = 1, solids = false})
    pbf.run(0)
  )");
  const auto r = run_engine("run " + (dir / "tank.lua").string() + " -v OUT=" + dir.string());
  ASSERT_EQ(r.code, 0) << r.output;
  const double s = 0.01, height = 0.2;
  // The top inside the tank, up to its walls but for its edges: the vertices above H - s/2,
  // their mean height and their normals' largest tilt from the vertical.
  struct Top {
    double height = 0, tilt = 0;
  };
  auto top = [&](const Ply& ply) {
    Top t;
    double count = 0;
    for (std::size_t v = 0; v < ply.mesh.vertices.size(); ++v) {
      const auto& x = ply.mesh.vertices[v];
      if (x[2] < height - s / 2 || x[0] < 0 || x[0] > 0.1 || x[1] < 0 || x[1] > 0.1) continue;
      // (Within R of the tank's vertical edges a particle is mirrored across the nearer face only.)
      if (std::min(x[0], 0.1 - x[0]) < 2 * s && std::min(x[1], 0.1 - x[1]) < 2 * s) continue;
      t.height += x[2], count += 1;
      t.tilt = std::max(t.tilt, std::acos(std::min(1.0f, ply.normals[v][2])) * 180 / std::numbers::pi);
    }
    EXPECT_GT(count, 100);
    t.height /= count;
    return t;
  };
  const Ply mirrored = read_ply(dir / "mirrored_00000.ply"), plain = read_ply(dir / "plain_00000.ply");
  for (const Ply* ply : {&mirrored, &plain}) {
    EXPECT_EQ(manifold_defect(ply->mesh), "");
    EXPECT_EQ(pieces(ply->mesh), 1u);
  }
  const Top with = top(mirrored), without = top(plain);
  // Mirrored, the top is flat at the column's height right up to the walls (as at the domain's
  // walls: within 5 degrees); without, it rounds off into them (the kernels there see half a
  // neighbourhood), tilting steeply.
  EXPECT_NEAR(with.height, height, s / 4);
  EXPECT_LT(with.tilt, 5.0);
  EXPECT_GT(without.tilt, 30.0);
  // The mirrored surface runs on into the tank's walls (hidden by them) and closes there: no
  // vertex lies beyond the mirrored fluid's reach (R and half a spacing), and none in the
  // domain's walls' gap around the tank beyond it.
  double deepest = 0;
  for (const auto& x : mirrored.mesh.vertices)
    deepest = std::max({deepest, -x[0], x[0] - 0.1, -x[1], x[1] - 0.1, -x[2]});
  EXPECT_GT(deepest, s / 2);
  EXPECT_LT(deepest, 2 * s + s / 2 + s / 4);
}

TEST(DumpSurface, DamBreakMeshesAreClosedManifoldsAtEveryFrameSplashesIncludedAndTheSameAtAnyThreadCount) {
  auto one = test::temp_dir("surface-dam-1"), two = test::temp_dir("surface-dam-2");
  const auto r1 = dam_break_surfaces(one, 1), r2 = dam_break_surfaces(two, 2);
  ASSERT_EQ(r1.code, 0) << r1.err;
  ASSERT_EQ(r2.code, 0) << r2.err;
  std::size_t most_pieces = 0;
  for (int frame = 0; frame <= 6; ++frame) {
    const std::string name = fmt::format("out/surface/surface_{:05d}", frame);
    SCOPED_TRACE(name);
    for (const char* ext : {".vtp", ".ply"}) {
      ASSERT_TRUE(std::filesystem::exists(one / (name + ext)));
      EXPECT_EQ(read_file(one / (name + ext)), read_file(two / (name + ext))) << "differs at 1 and 2 threads";
    }
    const Ply ply = read_ply(one / (name + ".ply"));
    EXPECT_EQ(manifold_defect(ply.mesh), "");
    EXPECT_EQ(self_intersections(ply.mesh, 0.0035), 0u);
    EXPECT_GT(enclosed_volume(ply.mesh), 0);  // outward
    most_pieces = std::max(most_pieces, pieces(ply.mesh));
  }
  EXPECT_GE(most_pieces, 3u) << "no splash: the test does not cover small pieces";
  // The collection lists the seven .vtp frames with their times.
  const std::string pvd = read_file(one / "out/surface/surface.pvd");
  EXPECT_NE(pvd.find("surface_00006.vtp"), std::string::npos);
  EXPECT_NE(pvd.find("timestep=\"0.6"), std::string::npos) << pvd;
}

TEST(DumpSurface, OtherFormatsBesideAndPicturesOfTheWater) {
  auto dir = test::temp_dir("surface-formats");
  test::write_file(dir / "drop.lua", R"(
    pbf.domain{lo = {0, 0, 0}, hi = {0.2, 0.2, 0.2}}
    pbf.kernel_radius(0.02)
    pbf.timestep(0.001)
    pbf.lattice{lo = {0.05, 0.05, 0.05}, hi = {0.1, 0.1, 0.1}, spacing = 0.01}
    pbf.fix("pbf", "pbf", {})
    pbf.fix("walls", "box", {})
    pbf.fix("surface", "dump/surface", {path = var.OUT .. "/s_*.obj", also = {"ply", "vdb", "vtp"}, every = 5})
    pbf.fix("water", "dump/image", {path = var.OUT .. "/w_*.png", draw = "surface", every = 5, width = 64, height = 48})
    pbf.run(5)
  )");
  const auto r = run_engine("run " + (dir / "drop.lua").string() + " -v OUT=" + dir.string());
  ASSERT_EQ(r.code, 0) << r.output;
  for (const char* f : {"s_00001.obj", "s_00001.ply", "s_00001.vdb", "s_00001.vtp", "s.pvd", "w_00001.png"})
    EXPECT_TRUE(std::filesystem::exists(dir / f)) << f;
  const std::string obj = read_file(dir / "s_00001.obj");
  EXPECT_NE(obj.find("\nv "), std::string::npos);
  EXPECT_NE(obj.find("\nf "), std::string::npos);
  EXPECT_EQ(read_file(dir / "s_00001.vdb").substr(0, 4), std::string("\x20\x42\x44\x56", 4));  // OpenVDB's magic
}

TEST(DumpSurface, ARestartContinuesTheFramesAndTheCollection) {
  auto straight = test::temp_dir("surface-straight"), split = test::temp_dir("surface-split");
  const std::string args = " -v particles=2000 -v out=out -v surface=0.05 -v interval=1 --log none";
  ASSERT_EQ(test::run_in(straight, "run " + scenario("dambreak.lua") + " -v t_end=0.2 -v restart_interval=0" + args).code, 0);
  ASSERT_EQ(test::run_in(split, "run " + scenario("dambreak.lua") + " -v t_end=0.1 -v restart_interval=0.1" + args).code, 0);
  std::string restart;
  for (const auto& e : std::filesystem::directory_iterator(split / "out"))
    if (e.path().extension() == ".restart") restart = e.path().string();
  ASSERT_FALSE(restart.empty());
  const auto r = test::run_in(split, "run " + scenario("dambreak.lua") + " -v t_end=0.2 -v restart=" + restart + args);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(read_file(straight / "out/surface/surface.pvd"), read_file(split / "out/surface/surface.pvd"));
  EXPECT_EQ(read_file(straight / "out/surface/surface_00004.ply"), read_file(split / "out/surface/surface_00004.ply"));
}

TEST(DumpSurface, BadParametersAreOneClearMessage) {
  auto dir = test::temp_dir("surface-bad");
  auto fails = [&](const std::string& params, const std::string& says) {
    test::write_file(dir / "bad.lua", R"(
      pbf.domain{lo = {0, 0, 0}, hi = {0.2, 0.2, 0.2}}
      pbf.kernel_radius(0.02)
      pbf.timestep(0.001)
      pbf.lattice{lo = {0.05, 0.05, 0.05}, hi = {0.1, 0.1, 0.1}, spacing = 0.01}
      pbf.fix("pbf", "pbf", {})
      pbf.fix("surface", "dump/surface", {every = 1, )" + params + R"(})
      pbf.run(1)
    )");
    const auto r = run_engine("run " + (dir / "bad.lua").string() + " -v OUT=" + dir.string());
    EXPECT_NE(r.code, 0) << params;
    EXPECT_NE(r.output.find(says), std::string::npos) << params << "\n" << r.output;
  };
  fails("path = var.OUT .. '/s_*.stl'", "must end in .vtp, .ply, .obj or .vdb");
  fails("voxel = 0", "voxel");
  fails("voxel = -1", "voxel");
  fails("radius = 0/0", "radius");
  fails("radius = 0.2, voxel = 0.5", "at least the voxel");
  fails("iso = 1.5", "iso");
  fails("kernel = 'anisotropc'", "anisotropic");
  fails("walls = 'shut'", "closed");
  fails("fields = {'id'}", "not a value a surface can carry");
  fails("voxel = 0.001, memory = 1", "raise 'memory' or the voxel size");
  fails("path = '/proc/nonexistent/s_*.ply'", "/proc/nonexistent");
}

}  // namespace
}  // namespace pbf
