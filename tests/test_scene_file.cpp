// The original study's scene format: a good file loads with the mass rule; every malformed
// case is refused with FILE:LINE.
#include <gtest/gtest.h>

#include "engine/core/error.hpp"
#include "engine/io/scene_file.hpp"
#include "engine/core/simulation.hpp"
#include "test_util.hpp"

using namespace pbf;

namespace {

const std::string kHeader = "0.002\n0.04\n0.4\n0.01\n0.03\n";

std::string error_of(const std::string& text) {
  const auto dir = test::temp_dir("scene");
  const auto path = dir / "scene.txt";
  test::write_file(path, text);
  try {
    read_scene_file(path.string());
  } catch (const Error& e) {
    EXPECT_TRUE(e.located());
    return e.what();
  }
  return "";
}

void expect_error(const std::string& text, int line, const std::string& words) {
  const std::string e = error_of(text);
  EXPECT_NE(e.find("scene.txt:" + std::to_string(line) + ": "), std::string::npos) << e;
  EXPECT_NE(e.find(words), std::string::npos) << e;
}

}  // namespace

TEST(SceneFile, ReadsHeaderOnOneLineOrSeveralWithComments) {
  const auto dir = test::temp_dir("scene-ok");
  test::write_file(dir / "a.txt", "# a comment\n2 0.002 0.04\n0.4 0.01\n  # another\n0.03\n0.1 0.1 0.1 0 0 -1\n\n0.2 0.1 0.1 1 0 0\n");
  const SceneFile s = read_scene_file((dir / "a.txt").string());
  EXPECT_EQ(s.count, 2);
  EXPECT_DOUBLE_EQ(s.dt, 0.002);
  EXPECT_DOUBLE_EQ(s.h, 0.04);
  EXPECT_DOUBLE_EQ(s.L, 0.4);
  EXPECT_DOUBLE_EQ(s.interval, 0.01);
  EXPECT_DOUBLE_EQ(s.t_final, 0.03);
  ASSERT_EQ(s.particles.size(), 12u);
  EXPECT_DOUBLE_EQ(s.particles[5], -1.0);
  EXPECT_DOUBLE_EQ(s.particles[9], 1.0);
}

TEST(SceneFile, MalformedFilesNameTheLine) {
  expect_error("3\n" + kHeader + "0.1 0.1 0.1 0 0 0\n0.2 0.1 0.1 0 0 0\n", 8, "found 2 particle line(s)");
  expect_error("1\n" + kHeader + "0.1 0.1 0.1 0 0 0\n0.2 0.1 0.1 0 0 0\n", 8, "more particle lines than the count");
  expect_error("2\n" + kHeader + "0.1 0.1 abc 0 0 0\n0.2 0.1 0.1 0 0 0\n", 7, "'abc' is not a number");
  expect_error("2\n" + kHeader + "0.1 nan 0.1 0 0 0\n0.2 0.1 0.1 0 0 0\n", 7, "not a finite number");
  expect_error("2\n" + kHeader + "0.1 0.1 0.9 0 0 0\n0.2 0.1 0.1 0 0 0\n", 7, "outside the domain");
  expect_error("2\n" + kHeader + "0.1 0.1 -0.1 0 0 0\n0.2 0.1 0.1 0 0 0\n", 7, "outside the domain");
  expect_error("2\n" + kHeader + "0.1 0.1 0.1 0 0\n0.2 0.1 0.1 0 0 0\n", 7, "expected 6 values");
  expect_error("2\n0.002\n-0.04\n0.4\n0.01\n0.03\n", 3, "particle size h must be positive");
  expect_error("2\n0\n0.04\n0.4\n0.01\n0.03\n", 2, "time step must be positive");
  expect_error("2\n0.002\n0.04\n0\n0.01\n0.03\n", 4, "domain side L must be positive");
  expect_error("2\n0.002\n0.04\n0.4\n-1\n0.03\n", 5, "output interval must be positive");
  expect_error("2\n0.002\n0.04\n0.4\n0.01\n0\n", 6, "final time must be positive");
  expect_error("2.5\n" + kHeader, 1, "not an integer");
  expect_error("0\n" + kHeader, 1, "must be positive");
  expect_error("2\n0.002\n0.04\n", 3, "header ends early");
  expect_error("2\n0.002 0.04 0.4 0.01 0.03 7\n", 2, "unexpected '7'");
}

TEST(SceneFile, AcceptsAByteOrderMarkAndWindowsLineEnds) {
  const auto dir = test::temp_dir("scene-bom");
  test::write_file(dir / "a.txt", "\xEF\xBB\xBF" "1 0.002 0.04 0.4 0.01 0.03\r\n+0.1 0.1 0.1 0 0 -1\r\n");
  const SceneFile s = read_scene_file((dir / "a.txt").string());
  EXPECT_EQ(s.count, 1);
  EXPECT_DOUBLE_EQ(s.particles[0], 0.1);
}

TEST(SceneFile, MalformedNumbersSayWhatIsWrong) {
  expect_error("1\n" + kHeader + "+-0.1 0.1 0.1 0 0 0\n", 7, "x: '+-0.1' is not a number");  // was read as -0.1
  expect_error("1\n" + kHeader + "0.1 0.1 0.1 1e400 0 0\n", 7, "vx: '1e400' is out of the range of a double");
  expect_error("99999999999999999999\n" + kHeader, 1, "particle count N: '99999999999999999999' is too large");
  if (sizeof(real) == 4) {  // a float build: values it cannot hold
    expect_error("1\n" + kHeader + "0.1 0.1 0.1 1e39 0 0\n", 7, "vx: '1e39' is too large for the particle data");
    expect_error("1\n0.002\n1e-50\n0.4\n0.01\n0.03\n", 3, "'1e-50' is too small for the particle data");
  }
}

TEST(SceneFile, ADirectoryOrADeviceIsAnError) {
  const auto dir = test::temp_dir("scene-dir");
  try {
    read_scene_file(dir.string());
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), dir.string() + ": cannot open scene file: it is a directory");
  }
  // A device would be read for ever (and a FIFO would block the open): refused at once.
  try {
    read_scene_file("/dev/zero");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "/dev/zero: cannot open scene file: it is not a regular file (a device, a pipe "
                                     "or a socket)");
  }
}

TEST(SceneFile, AHugeCountWithoutDataIsAnErrorNotAnAllocation) {
  expect_error("999999999999\n" + kHeader + "0.1 0.1 0.1 0 0 0\n", 7, "found 1 particle line(s)");
}

TEST(SceneFile, MissingFileIsAnError) {
  try {
    read_scene_file("/nonexistent/scene.txt");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/scene.txt: cannot open"), std::string::npos);
  }
}

TEST(SceneFile, MassGivesInteriorParticlesTheRestDensity) {
  // A 12^3 lattice of spacing 0.01 with h = 0.02 in a box of side 0.12: the interior
  // particles (at least h from every face) have exactly rho0, as the original code did.
  const auto dir = test::temp_dir("scene-mass");
  std::string text = "1728 0.001 0.02 0.12 0.01 0.02\n";
  for (int k = 0; k < 12; ++k)
    for (int j = 0; j < 12; ++j)
      for (int i = 0; i < 12; ++i)
        text += std::to_string((i + 0.5) * 0.01) + " " + std::to_string((j + 0.5) * 0.01) + " " +
                std::to_string((k + 0.5) * 0.01) + " 0 0 0\n";
  test::write_file(dir / "lattice.txt", text);
  Simulation sim;
  load_scene(sim, read_scene_file((dir / "lattice.txt").string()));
  const auto& rho = sim.summed_density();
  const auto& P = sim.particles();
  int interior = 0;
  for (std::size_t i = 0; i < P.size(); ++i) {
    const real c[3] = {P.x()[i], P.y()[i], P.z()[i]};
    bool inside = true;
    for (real v : c) inside = inside && v >= 0.02 && v <= 0.1;
    if (!inside) continue;
    ++interior;
    EXPECT_NEAR(rho[i] / 1000.0, 1.0, test::kRounding);
  }
  EXPECT_GT(interior, 100);
}
