// Divergence-free SPH (engine/fixes/dfsph.cpp, issue 34): a resting column stays still in the
// box and in a mesh container; each solve reaches its tolerance, and says once when its cap
// stops it short; and bad input (tolerances, caps, a second solver, a step beyond the CFL
// bound) is one clear message. The hydrostatic pressure it carries is tests/test_probe.cpp's;
// its bits at any thread count, across restarts and with the ghosts checked are
// tests/pipelines.hpp's (DfsphCflLaplacianViscosity, DfsphMovingSolidFloatingBody).
#include <gtest/gtest.h>

#include <string>

#include "test_util.hpp"

using pbf::test::read_csv;
using pbf::test::run_engine;
using pbf::test::temp_dir;
using pbf::test::write_file;

namespace {

const std::string kShare = std::string(PBF_SOURCE_DIR) + "/share";
const std::string kGeometry = std::string(PBF_SOURCE_DIR) + "/scenarios/geometry";

// A column of water H = 0.2 m deep on a 0.1 m square floor at spacing s = 1 cm (2,000
// particles, h = 2s), in the box or in a mesh container of the same size (var.walls = "mesh"),
// with dfsph, a Laplacian viscosity nu and the CFL step; the speeds and the solves' iterations
// every 0.1 s into var.dir/t.csv. The rest of the script follows.
std::string column(const std::string& rest) {
  return "package.path = var.share .. '/lua/?.lua;' .. package.path\n"
         "local H, W, s = 0.2, 0.1, 0.01\n"
         "pbf.domain{lo = {0, 0, 0}, hi = {W, W, 1.5 * H}}\n"
         "pbf.kernel_radius(2 * s)\n"
         "pbf.timestep(0.004)\n"
         "pbf.lattice{lo = {0, 0, 0}, hi = {W, W, H}, spacing = s}\n"
         "pbf.fix('gravity', 'gravity', {})\n"
         "require('solvers').dfsph{error = var.error, divergence_error = var.divergence_error, nu = var.nu,\n"
         "                         max_iterations = var.max_iterations}\n"
         "if var.walls == 'mesh' then\n"
         "  pbf.fix('walls', 'solid', {file = var.geometry .. '/unit_box.obj', scale = {W, W, 1.5 * H}, fluid = 'inside'})\n"
         "else\n"
         "  pbf.fix('walls', 'box', {})\n"
         "end\n"
         "pbf.compute('v', 'speed')\n"
         "pbf.compute('it', 'iterations')\n"
         "pbf.compute('div', 'iterations', {loop = 'divergence'})\n"
         "pbf.fix('s', 'sample', {computes = {'v', 'it', 'div'}, interval = 0.1, file = var.dir .. '/t.csv'})\n" +
         rest;
}

pbf::test::Result run_column(const std::filesystem::path& dir, const std::string& rest, const std::string& vars) {
  write_file(dir / "a.lua", column(rest));
  return run_engine("run " + (dir / "a.lua").string() + " -v share=" + kShare + " -v geometry=" + kGeometry +
                    " -v dir=" + dir.string() + vars);
}

// After 1 s, the mean speed and the largest below `mean` and `most`. The column starts on a
// lattice with no pressure; what moves it after its first steps is the lattice settling, which
// the viscosity damps (nu = 1e-3 m^2/s, numerical: at water's 1e-6 it rings on, as it does under
// every solver here without its damping), and the solves' remaining error, whose smoothest part
// (the column breathing) leaves a speed of about error H / dt: 1e-4 * 0.2 m / 0.004 s = 5 mm/s
// at the default tolerance, 0.5 mm/s at 1e-5 (docs/validation/dfsph.md). Every step meets its
// tolerances: no warning of a cap, and the errors reported within them.
void expect_still(const std::string& walls, double mean, double most) {
  const auto dir = temp_dir("dfsph-still");
  auto r = run_column(dir, "pbf.run_until(1.0)\n",
                      " -v error=1e-5 -v divergence_error=1e-4 -v nu=1e-3 -v max_iterations=1000 -v walls=" + walls);
  ASSERT_EQ(r.code, 0) << r.output;
  const auto csv = read_csv(dir / "t.csv");
  ASSERT_NEAR(csv.at("time").back(), 1.0, 1e-9);
  EXPECT_LT(csv.at("v.avg").back(), mean) << walls;
  EXPECT_LT(csv.at("v.max").back(), most) << walls;
  EXPECT_EQ(r.output.find("stopped at its cap"), std::string::npos) << r.output;
  for (double e : csv.at("it.error")) EXPECT_LE(e, 1e-5);
  for (double e : csv.at("div.error")) EXPECT_LE(e, 1e-4);
}

// The mean, 5 mm/s; the fastest particle within the other solvers' still column's
// 5 cm/s (tests/test_scenarios.cpp, issue 10): measured 2026-11-28 in the box 1.5 mm/s and
// 20 mm/s (the 2 cm/s: a particle near the floor still settling; open,
// docs/validation/dfsph.md), in the mesh container 2 and 37 mm/s.
TEST(Dfsph, ColumnAtRestInTheBoxIsStill) { expect_still("box", 0.005, 0.05); }

TEST(Dfsph, ColumnAtRestInAMeshContainerIsStill) { expect_still("mesh", 0.005, 0.05); }

TEST(Dfsph, ASolveStoppedByItsCapSaysSoOnceAndTheRunGoesOn) {
  const auto dir = temp_dir("dfsph-cap");
  auto r = run_column(dir, "pbf.run(20)\n", " -v error=1e-9 -v max_iterations=2");
  ASSERT_EQ(r.code, 0) << r.output;
  const std::string said = "the constant-density solve stopped at its cap of 2 iterations in step 1";
  ASSERT_NE(r.output.find(said), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("constant-density solve stopped", r.output.find(said) + said.size()), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("(tolerance 1e-09)"), std::string::npos) << r.output;
}

// Bad input: one message naming the parameter (or the two solvers), and a non-zero exit.
TEST(Dfsph, BadInputIsOneClearError) {
  const auto dir = temp_dir("dfsph-bad");
  struct Case {
    std::string script, expected;
  };
  const std::string scene =
      "pbf.domain{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.2}}\npbf.kernel_radius(0.02)\npbf.timestep(0.002)\n"
      "pbf.lattice{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.1}, spacing = 0.01}\npbf.fix('g', 'gravity', {})\n";
  const Case cases[] = {
      {"pbf.fix('d', 'dfsph', {error = 0})", "parameter 'error'"},
      {"pbf.fix('d', 'dfsph', {error = -1e-4})", "parameter 'error'"},
      {"pbf.fix('d', 'dfsph', {divergence_error = 0/0})", "parameter 'divergence_error'"},
      {"pbf.fix('d', 'dfsph', {divergence_error = math.huge})", "parameter 'divergence_error'"},
      {"pbf.fix('d', 'dfsph', {max_iterations = 0})", "parameter 'max_iterations'"},
      {"pbf.fix('d', 'dfsph', {divergence_max_iterations = 0})", "parameter 'divergence_max_iterations'"},
      {"pbf.fix('d', 'dfsph', {min_iterations = 5, max_iterations = 3})", "min_iterations = 5 exceeds max_iterations = 3"},
      {"pbf.fix('d', 'dfsph', {})\npbf.fix('w', 'wcsph', {})", "does the pressure solver already"},
      {"pbf.fix('d', 'dfsph', {})\npbf.fix('p', 'pbf', {})", "does the time integration already"},
      {"pbf.fix('i', 'leapfrog', {})\npbf.fix('d', 'dfsph', {})", "does the time integration already"},
      {"pbf.fix('d', 'dfsph', {})\npbf.fix('b', 'box', {})\npbf.timestep(0.2)\npbf.run(5)",
       "beyond DFSPH's CFL bound"},
  };
  int k = 0;
  for (const auto& c : cases) {
    const auto path = dir / ("bad" + std::to_string(k++) + ".lua");
    write_file(path, scene + c.script + "\n");
    auto r = run_engine("run " + path.string());
    EXPECT_NE(r.code, 0) << c.script;
    EXPECT_NE(r.output.find(c.expected), std::string::npos) << c.script << "\n" << r.output;
  }
}

}  // namespace
