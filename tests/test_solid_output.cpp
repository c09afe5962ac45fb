// Solids in the dumps: dump/vtk writes each solid's surface as a .vtp (parsed by an
// independent Python reader), once for a static solid and again when its surface version
// changes, lists the parts of every frame in the .pvd, and carries this across a restart;
// dump/image draws solids unless `solids = false`.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "engine/core/simulation.hpp"
#include "engine/io/bytes.hpp"
#include "engine/io/restart.hpp"
#include "engine/registry/style_registry.hpp"
#include "engine/sph/lattice.hpp"
#include "test_solids.hpp"
#include "test_util.hpp"

using namespace pbf;
using pbf::test::box_mesh;
using pbf::test::read_file;
using pbf::test::TestSolid;
using pbf::test::write_file;
namespace fs = std::filesystem;

namespace {

// 64 particles in the middle of the unit box.
void particles(Simulation& sim) {
  sim.set_domain(Domain{});
  sim.set_kernel_radius(0.1);
  sim.set_timestep(0.001);
  const double lo[3] = {0.4, 0.4, 0.4}, hi[3] = {0.6, 0.6, 0.6}, v[3] = {0, 0, 0};
  add_lattice(sim, lo, hi, 0.05, v);
}

// Those particles, a container around them ("tank", static) and an obstacle ("paddle", moved
// by the tests); returns the paddle.
TestSolid* scene(Simulation& sim) {
  particles(sim);
  sim.add_fix(std::make_unique<TestSolid>("tank", box_mesh({0.1, 0.1, 0.1}, {0.9, 0.9, 0.9}), true));
  auto paddle = std::make_unique<TestSolid>("paddle", box_mesh({0.2, 0.2, 0.2}, {0.3, 0.3, 0.3}), false);
  TestSolid* p = paddle.get();
  sim.add_fix(std::move(paddle));
  return p;
}

void add_vtk(Simulation& sim, const fs::path& dir) {
  sim.add_fix(StyleRegistry::builtin().make_fix(
      "vtk", "dump/vtk",
      {{"path", (dir / "frame_*.vtu").string()}, {"every", std::int64_t{1}}, {"fields", Names{"id"}}}));
}

// What check_vtu.py prints for ARGS, and its exit status.
std::pair<int, std::string> check_vtu(const std::string& args) {
  const std::string command = fmt::format("'{}' '{}/tests/check_vtu.py' {} 2>&1", PBF_PYTHON, PBF_SOURCE_DIR, args);
  std::string out;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return {-1, ""};
  char buf[4096];
  std::size_t n;
  while ((n = fread(buf, 1, sizeof buf, pipe)) > 0) out.append(buf, n);
  return {pclose(pipe), out};
}

std::string dataset(const std::string& time, int part, const std::string& file) {
  return fmt::format("<DataSet timestep=\"{}\" group=\"\" part=\"{}\" file=\"{}\"/>", time, part, file);
}

}  // namespace

TEST(SolidOutput, TheBoxMeshIsOrientedOutward) {
  const TriangleMesh m = box_mesh({0, 0, 0}, {1, 2, 3});
  ASSERT_EQ(m.vertices.size(), 8u);
  ASSERT_EQ(m.triangles.size(), 12u);
  for (const auto& t : m.triangles) {
    const auto &a = m.vertices[t[0]], &b = m.vertices[t[1]], &c = m.vertices[t[2]];
    const std::array<double, 3> u{b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const std::array<double, 3> n{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    double outward = 0;  // the normal against the offset from the box centre to the triangle
    for (int k = 0; k < 3; ++k) outward += n[k] * ((a[k] + b[k] + c[k]) / 3 - (k + 1) * 0.5);
    EXPECT_GT(outward, 0);
  }
}

TEST(SolidOutput, VtkWritesSurfacesWhenTheyChangeAndThePvdListsThemAsParts) {
  const auto dir = test::temp_dir("solid-vtk");
  Simulation sim;
  TestSolid* paddle = scene(sim);
  add_vtk(sim, dir);
  sim.run(1);  // frames 0, 1
  // The static tank is written once: a marker in its place survives the later frames.
  ASSERT_TRUE(fs::exists(dir / "frame_solid_tank.vtp"));
  const std::string tank = read_file(dir / "frame_solid_tank.vtp");
  write_file(dir / "frame_solid_tank.vtp", "marker");
  paddle->lift(0.1);
  sim.run(2);  // frames 2 (the paddle moved) and 3
  EXPECT_EQ(read_file(dir / "frame_solid_tank.vtp"), "marker");
  write_file(dir / "frame_solid_tank.vtp", tank);

  std::vector<std::string> surfaces;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.path().extension() == ".vtp") surfaces.push_back(entry.path().filename().string());
  std::sort(surfaces.begin(), surfaces.end());
  EXPECT_EQ(surfaces, (std::vector<std::string>{"frame_solid_paddle.vtp", "frame_solid_paddle_00002.vtp",
                                                "frame_solid_tank.vtp"}));
  const std::string pvd = read_file(dir / "frame.pvd");
  for (int frame = 0; frame < 4; ++frame) {
    const std::string time = frame == 0 ? "0" : fmt::format("0.00{}", frame);
    const std::string paddle_file = frame < 2 ? "frame_solid_paddle.vtp" : "frame_solid_paddle_00002.vtp";
    EXPECT_NE(pvd.find(dataset(time, 0, fmt::format("frame_{:05d}.vtu", frame)) + "\n    " +
                       dataset(time, 1, "frame_solid_tank.vtp") + "\n    " + dataset(time, 2, paddle_file)),
              std::string::npos)
        << pvd;
  }

  // A tank replaced between runs by another under the same name, version 0 again: found out
  // by its bytes, and written under a numbered name, leaving the earlier frames' file alone.
  sim.remove_fix("tank");
  sim.add_fix(std::make_unique<TestSolid>("tank", box_mesh({0.05, 0.05, 0.05}, {0.95, 0.95, 0.95}), true));
  sim.run(1);  // frame 4
  EXPECT_TRUE(fs::exists(dir / "frame_solid_tank_00004.vtp"));
  EXPECT_EQ(read_file(dir / "frame_solid_tank.vtp"), tank);
  EXPECT_NE(read_file(dir / "frame.pvd").find(dataset("0.004", 2, "frame_solid_tank_00004.vtp")), std::string::npos);

  if (std::string(PBF_PYTHON).empty()) GTEST_SKIP() << "no Python interpreter";
  for (const char* file : {"frame_solid_tank.vtp", "frame_solid_paddle_00002.vtp"}) {
    const auto [status, out] = check_vtu("'" + (dir / file).string() + "'");
    EXPECT_EQ(status, 0) << out;
    EXPECT_EQ(out, "points 8\ntriangles 12\n") << file;
  }
  const auto [status, out] = check_vtu("--pvd '" + (dir / "frame.pvd").string() + "'");
  EXPECT_EQ(status, 0) << out;
  EXPECT_NE(out.find("0.003 2 frame_solid_paddle_00002.vtp\n"), std::string::npos) << out;
}

TEST(SolidOutput, ARestartContinuesTheSurfacesAndTheCollection) {
  const auto dir = test::temp_dir("solid-restart");
  std::string straight;
  {
    Simulation sim;
    TestSolid* paddle = scene(sim);
    add_vtk(sim, dir / "a");
    sim.run(2);
    write_restart(sim, (dir / "r").string());
    paddle->lift(0.1);
    sim.run(2);
    straight = read_file(dir / "a" / "frame.pvd");
  }
  fs::rename(dir / "a", dir / "b");  // the continuation writes in place of the straight run
  fs::create_directories(dir / "a");
  fs::copy_file(dir / "b" / "frame_solid_tank.vtp", dir / "a" / "frame_solid_tank.vtp");
  Simulation sim;
  read_restart(sim, (dir / "r").string());
  sim.add_fix(std::make_unique<TestSolid>("tank", box_mesh({0.1, 0.1, 0.1}, {0.9, 0.9, 0.9}), true));
  auto paddle = std::make_unique<TestSolid>("paddle", box_mesh({0.2, 0.2, 0.2}, {0.3, 0.3, 0.3}), false);
  paddle->lift(0.1);
  sim.add_fix(std::move(paddle));
  add_vtk(sim, dir / "a");
  sim.run(2);
  EXPECT_EQ(read_file(dir / "a" / "frame.pvd"), straight);
  EXPECT_TRUE(fs::exists(dir / "a" / "frame_solid_paddle_00003.vtp"));
  EXPECT_FALSE(fs::exists(dir / "a" / "frame_solid_paddle.vtp"));  // unchanged: not written again
}

TEST(SolidOutput, AStateSavedWithoutSolidsStillReads) {
  // A dump's state from before solids ends after the frames; the solids' part of a state
  // with none is 8 bytes per frame and 16 more.
  Simulation sim;
  particles(sim);
  const auto dir = test::temp_dir("solid-old-state");
  add_vtk(sim, dir);
  sim.run(2);  // 3 frames
  ByteWriter w;
  sim.find_fix("vtk")->save_state(w);
  const std::vector<unsigned char> bytes = w.bytes();
  ASSERT_GT(bytes.size(), 8u * 5);
  auto fresh = StyleRegistry::builtin().make_fix(
      "vtk", "dump/vtk", {{"path", (dir / "frame_*.vtu").string()}, {"every", std::int64_t{1}}});
  ByteReader old(bytes.data(), bytes.size() - 8 * 5, "old state");
  fresh->restore_state(old);
  EXPECT_EQ(old.left(), 0u);
  ByteWriter again;
  fresh->save_state(again);
  EXPECT_EQ(again.bytes(), bytes);
}

TEST(SolidOutput, ImagesDrawSolidsUnlessSwitchedOff) {
  const auto dir = test::temp_dir("solid-image");
  auto render = [&](bool with_solids, bool draw, const std::string& name) {
    Simulation sim;
    particles(sim);
    if (with_solids) sim.add_fix(std::make_unique<TestSolid>("tank", box_mesh({0.1, 0.1, 0.1}, {0.9, 0.9, 0.9}), true));
    sim.add_fix(StyleRegistry::builtin().make_fix("img", "dump/image",
                                                  {{"path", (dir / (name + "_*.png")).string()},
                                                   {"width", std::int64_t{160}},
                                                   {"height", std::int64_t{120}},
                                                   {"solids", draw},
                                                   {"every", std::int64_t{1}}}));
    sim.run(1);
    return read_file(dir / (name + "_00001.png"));
  };
  const std::string none = render(false, true, "none"), off = render(true, false, "off"), on = render(true, true, "on");
  ASSERT_FALSE(none.empty());
  EXPECT_TRUE(off == none) << "solids = false still draws the solid";
  EXPECT_FALSE(on == none) << "the solid is not drawn";
}
