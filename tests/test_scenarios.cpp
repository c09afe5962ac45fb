// The scenarios, run small through the pbfengine binary: the hydrostatic column stays at
// rest at two resolutions, the dam break surges forward, and a run has the same bits at 1
// and 2 threads.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <vector>

#include "test_util.hpp"

using pbf::test::run_engine;
using pbf::test::scenario;
using pbf::test::read_csv;

namespace {

// Compares every file of run `a`'s output directory with the same-named file of run `b`'s, byte
// for byte (`what` names the case in failures); returns how many it compared.
int compare_outputs(const std::filesystem::path& a, const std::filesystem::path& b, const std::string& what) {
  int compared = 0;
  for (const auto& e : std::filesystem::directory_iterator(a)) {
    EXPECT_EQ(pbf::test::read_file(e.path()), pbf::test::read_file(b / e.path().filename()))
        << what << " " << e.path().filename();
    ++compared;
  }
  return compared;
}

}  // namespace

class Hydrostatic : public ::testing::TestWithParam<int> {};

TEST_P(Hydrostatic, ColumnStaysAtRest) {
  const int particles = GetParam();
  const auto dir = pbf::test::temp_dir("hydrostatic");
  auto r = run_engine("run " + scenario("hydrostatic.lua") + " -v particles=" + std::to_string(particles) +
                      " -v t_end=3 -v csv=" + (dir / "thermo.csv").string());
  ASSERT_EQ(r.code, 0) << r.output;
  auto c = read_csv(dir / "thermo.csv");
  ASSERT_GT(c["time"].size(), 20u);
  const double H = 0.4, W = 0.2, g = 9.81;
  const double s = std::cbrt(W * W * H / particles);  // the scenario's spacing, to a few percent
  const double top0 = c["top"].front();
  for (std::size_t k = 0; k < c["time"].size(); ++k) {
    if (c["time"][k] < 1.0) continue;  // after the initial settling
    // Height: the free-surface layer may sink into the next by up to a spacing (a one-sided
    // constraint does not hold particles that lack neighbours), the first layer may come half
    // a spacing closer to the floor, and the column compresses by its average compression.
    EXPECT_GT(c["top"][k], top0 - 1.5 * s - 0.02 * H) << "t = " << c["time"][k];
    // Average compression: 4 iterations leave 2.5% (2000 particles) and 2.7% (5000), measured
    // 2026-11-28 (docs/physics.md, "Iterations": 2.6%, growing with the column's depth in
    // particles); 3% is where pbf warns that its step or count is too small for the fluid.
    EXPECT_LT(c["err.compression"][k], 0.03) << "t = " << c["time"][k];
    // Residual motion, against the free-fall speed over the column, sqrt(2 g H) = 2.8 m/s:
    // the solver leaves particles jostling at 0.5% of it on average and 4% at most (measured
    // 2026-11-28); a collapse or a slosh moves the whole column at a good fraction of it.
    EXPECT_LT(c["v.avg"][k], 0.04 * std::sqrt(2 * g * H)) << "t = " << c["time"][k];
    EXPECT_LT(c["v.max"][k], 0.25 * std::sqrt(2 * g * H)) << "t = " << c["time"][k];
    EXPECT_GE(c["box.zmin"][k], 0.0);
  }
}

INSTANTIATE_TEST_SUITE_P(TwoResolutions, Hydrostatic, ::testing::Values(2000, 5000));

// The column of issue 10, 0.12 m deep at 10 mm spacing (on 0.24 m square for PBF at dt = 2
// ms, 4 iterations; on 0.12 m square for WCSPH, whose steps are ten times smaller), every
// style at its defaults: the walls keep particles half a spacing (their radius) off the faces
// and PBF's Jacobi relaxation 0.7 converges (docs/physics.md, "A column at rest"). Still
// after 1 s: mean speed below 0.01 m/s and no particle above 0.05 m/s (a settled column has
// no speed but its noise; 0.05 m/s is a 0.1 mm displacement in a 2 ms step), its top steady
// within 1% and within one spacing of where it started. In the analytic box, and in the same
// box as a mesh container (scenarios/geometry/unit_box.obj through the solid's density map),
// and as a layer periodic along x and y (no side walls: the lattice tiles the period, so the
// fluid continues through the faces as if endless; issue 32). WCSPH's layer rings longer: the
// column settles from zero pressure and starts the layer's acoustic mode (period 4 H / c0 =
// 0.03 s, velocity amplitude g H / c0 = 0.077 m/s at c0 = 10 sqrt(2 g H)), which stays one
// dimensional without side walls, where the box's walls turn it into shear that the artificial
// viscosity damps; its mean speed is bounded by a quarter of that amplitude after 1 s
// (measured 2026-11-28: at most 0.0102 m/s, against 0.0006 m/s in the box).
struct StillCase {
  const char* solver;
  const char* walls;
  const char* periodic = "";    // the domain's periodic axes
  double most_mean_speed = 0.01;  // m/s, after 1 s
};
void PrintTo(const StillCase& c, std::ostream* os) { *os << c.solver << " in " << c.walls << " " << c.periodic; }

class StillColumn : public ::testing::TestWithParam<StillCase> {};

// The largest speed: issue 10's 0.05 m/s in double precision. In single precision the surface
// layer's particles roll into the gaps below them more often (docs/physics.md, "Known limits":
// the fastest particle moves about 1.5 times as fast as in double, the mean speed is the same),
// so the bound is the speed of a fall through the 1 mm that layer settles, sqrt(2 g 1 mm).
const double kMostSpeed = sizeof(pbf::real) == 8 ? 0.05 : std::sqrt(2 * 9.81 * 0.001);

TEST_P(StillColumn, RestsAtTheDefaults) {
  const std::string solver = GetParam().solver, walls = GetParam().walls;
  const auto dir = pbf::test::temp_dir("still-column-" + solver + "-" + walls + GetParam().periodic);
  const std::string size = solver == "pbf" ? " -v particles=6912 -v width=0.24 -v dt=0.002"
                                           : " -v particles=1728 -v width=0.12";  // dfsph: its steps by cfl
  const std::string periodic = GetParam().periodic;
  auto r = run_engine("run " + scenario("hydrostatic.lua") + " -v solver=" + solver + " -v walls=" + walls +
                      " -v height=0.12" + size + " -v t_end=1.6 -v csv=" + (dir / "thermo.csv").string() +
                      (periodic.empty() ? "" : " -v periodic=" + periodic));
  ASSERT_EQ(r.code, 0) << r.output;
  auto c = read_csv(dir / "thermo.csv");
  const double s = 0.01, top0 = c["top"].front();
  double top1 = -1;
  int checked = 0;
  for (std::size_t k = 0; k < c["time"].size(); ++k) {
    if (c["time"][k] < 1.0) continue;
    if (top1 < 0) top1 = c["top"][k];
    EXPECT_LT(c["v.avg"][k], GetParam().most_mean_speed) << "t = " << c["time"][k];
    // (Without side walls the layer's surface particles roll into the gaps below them in double
    // precision too, measured 2026-11-28 up to 0.09 m/s: the fall through 1 mm bounds them.)
    const double most = periodic.empty() ? kMostSpeed : std::sqrt(2 * 9.81 * 0.001);
    EXPECT_LT(c["v.max"][k], most) << "t = " << c["time"][k];
    EXPECT_NEAR(c["top"][k], top1, 0.01 * top1) << "t = " << c["time"][k];
    EXPECT_NEAR(c["top"][k], top0, s) << "t = " << c["time"][k];
    ++checked;
  }
  EXPECT_GE(checked, 5);
}

INSTANTIATE_TEST_SUITE_P(BothSolvers, StillColumn,
                         ::testing::Values(StillCase{"pbf", "box"}, StillCase{"wcsph", "box"},
                                           StillCase{"pbf", "mesh"}, StillCase{"wcsph", "mesh"},
                                           StillCase{"dfsph", "box"}, StillCase{"dfsph", "mesh"},
                                           StillCase{"pbf", "box", "xy"},
                                           StillCase{"wcsph", "box", "xy", 0.25 * 9.81 * 0.12 / (10 * std::sqrt(2 * 9.81 * 0.12))}),
                         [](const ::testing::TestParamInfo<StillCase>& info) {
                           const std::string periodic = info.param.periodic;
                           return std::string(info.param.solver) + "_" + info.param.walls +
                                  (periodic.empty() ? "" : "_periodic_" + periodic);
                         });

TEST(DamBreak, SurgesForwardWithoutLosingParticles) {
  const auto dir = pbf::test::temp_dir("dambreak");
  auto r = run_engine("run " + scenario("dambreak.lua") + " -v particles=2000 -v t_end=0.15 -v out=" +
                      (dir / "out").string());
  ASSERT_EQ(r.code, 0) << r.output;
  auto c = read_csv(dir / "out" / "thermo.csv");
  const double a = 0.1, g = 9.81;
  ASSERT_GT(c["time"].size(), 5u);
  EXPECT_NEAR(c["front"].front() / a, 1.0, 0.05);  // the 99th percentile of x: 1 - 0.5 s / a = 0.96
  // By T = t sqrt(2g/a) = 2 the front has clearly left the column (Martin & Moyce: Z = 2.33 at
  // T = 1.98 and 2.56 at 2.20, read to 0.11; measured 2.45 at T = 2.09).
  const double T = c["time"].back() * std::sqrt(2 * g / a);
  ASSERT_GT(T, 2.0);
  EXPECT_GT(c["front"].back() / a, 2.0);
  // And no further than Ritter's dam break in shallow water, whose front runs at 2 sqrt(g H) from
  // t = 0 (H = 2a): Z <= 1 + 2 sqrt(2 g a) t / a = 1 + 2T. A real column must fall first; its front
  // lags (Martin & Moyce: Z = 4.11 at T = 3.33, against 7.66). Measured Z = 1.33 at T = 1.04
  // (bound 3.09), 2.45 at 2.09 (5.18): loose (the advance Z - 1 is a third of Ritter's), it
  // catches a front that runs away (particles shot ahead, gravity or pressure several times too strong).
  for (std::size_t k = 0; k < c["time"].size(); ++k)
    EXPECT_LE(c["front"][k] / a, 1 + 2 * c["time"][k] * std::sqrt(2 * g / a)) << "t = " << c["time"][k];
  // The last frame still holds every particle.
  std::string last;
  for (const auto& e : std::filesystem::directory_iterator(dir / "out"))
    if (e.path().filename().string().rfind("frame_", 0) == 0) last = std::max(last, e.path().string());
  std::istringstream frame(pbf::test::read_file(last));
  int count = 0, rows = 0;
  frame >> count;
  std::string line;
  std::getline(frame, line);
  while (std::getline(frame, line)) rows += !line.empty();
  EXPECT_EQ(count, rows);
  EXPECT_GT(count, 1500);
}

TEST(Determinism, SameBitsAtOneAndTwoThreads) {
  const auto dir = pbf::test::temp_dir("threads");
  for (int t : {1, 2}) {
    auto r = run_engine("run " + scenario("dambreak.lua") + " -v particles=2000 -v t_end=0.05 -v interval=0.01 " +
                        "--threads " + std::to_string(t) + " -v out=" + (dir / std::to_string(t)).string());
    ASSERT_EQ(r.code, 0) << r.output;
  }
  int compared = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir / "1")) {
    const auto other = dir / "2" / e.path().filename();
    ASSERT_TRUE(std::filesystem::exists(other)) << other;
    EXPECT_EQ(pbf::test::read_file(e.path()), pbf::test::read_file(other)) << e.path().filename();
    ++compared;
  }
  EXPECT_GE(compared, 6);  // five frames and the thermo CSV
}

// The obstacle scene (a ramp read from an STL file) runs through the surge's impact on the
// ramp (at about t = 0.2 s; a particle found inside the ramp would stop the run), and its
// ParaView frames (particles and the ramp's surface) are the same bytes at 1 and 2 threads.
TEST(Obstacle, SurgeMeetsTheRampSameBitsAtOneAndTwoThreads) {
  const auto dir = pbf::test::temp_dir("obstacle");
  for (int t : {1, 2}) {
    auto r = run_engine("run " + scenario("obstacle.lua") + " -v particles=3000 -v t_end=0.3 -v vtk=0.1 " +
                        "--threads " + std::to_string(t) + " -v out=" + (dir / std::to_string(t)).string());
    ASSERT_EQ(r.code, 0) << r.output;
  }
  int compared = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir / "1" / "vtk")) {
    const auto other = dir / "2" / "vtk" / e.path().filename();
    ASSERT_TRUE(std::filesystem::exists(other)) << other;
    EXPECT_EQ(pbf::test::read_file(e.path()), pbf::test::read_file(other)) << e.path().filename();
    ++compared;
  }
  EXPECT_GE(compared, 6);  // four particle frames, the ramp's surface, the collection
}

// The wave flume (a paddle driven by a Lua function, gauges sampled to a CSV) writes the same
// bytes at 1 and 2 threads with either solver: its ParaView frames, the paddle's surface at
// each frame (it moves, so each frame has its own), and the gauges' CSV.
TEST(WaveFlume, PaddleAndGaugesSameBitsAtOneAndTwoThreads) {
  for (const std::string solver : {"wcsph", "pbf"}) {
    const auto dir = pbf::test::temp_dir("flume-" + solver);
    for (int t : {1, 2}) {
      auto r = run_engine("run " + scenario("wave_flume.lua") + " -v solver=" + solver +
                          " -v spacing=0.04 -v start=0 -v t_end=0.3 -v vtk=0.1 --threads " + std::to_string(t) +
                          " -v out=" + (dir / std::to_string(t)).string());
      ASSERT_EQ(r.code, 0) << r.output;
    }
    int compared = 0, paddles = 0;
    for (const auto& e : std::filesystem::directory_iterator(dir / "1" / "vtk")) {
      const auto other = dir / "2" / "vtk" / e.path().filename();
      ASSERT_TRUE(std::filesystem::exists(other)) << other;
      EXPECT_EQ(pbf::test::read_file(e.path()), pbf::test::read_file(other)) << solver << " " << e.path().filename();
      paddles += e.path().filename().string().find("paddle") != std::string::npos;
      ++compared;
    }
    EXPECT_GE(paddles, 3) << solver;  // the paddle's surface at t = 0.1, 0.2, 0.3 s (t = 0 too, unless it had not moved)
    EXPECT_EQ(pbf::test::read_file(dir / "1" / "gauges.csv"), pbf::test::read_file(dir / "2" / "gauges.csv")) << solver;
    EXPECT_GE(compared, 8) << solver;
  }
}

// The fountain (an emitter and a drain) with either solver: its frames and thermo are the same
// bytes at 1 and 2 threads, the count is the pool's plus what came in less what went out,
// and the jet has reached the drain (some left) within 0.6 s.
TEST(Fountain, ComesAndGoesSameBitsAtOneAndTwoThreads) {
  for (const std::string solver : {"pbf", "wcsph"}) {
    const auto dir = pbf::test::temp_dir("fountain-" + solver);
    for (int t : {1, 2}) {
      auto r = run_engine("run " + scenario("fountain.lua") + " -v solver=" + solver + " -v s=0.02 -v t_end=0.6" +
                          " -v interval=0.2 -v restart_interval=0 --threads " + std::to_string(t) + " -v out=" +
                          (dir / std::to_string(t)).string());
      ASSERT_EQ(r.code, 0) << r.output;
    }
    const int compared = compare_outputs(dir / "1", dir / "2", solver);
    EXPECT_GE(compared, 5) << solver;  // four frames and the thermo CSV
    const auto thermo = pbf::test::read_csv(dir / "1" / "thermo.csv");
    const auto& n = thermo.at("n");
    const double in = thermo.at("in.count").back(), out = thermo.at("out.count").back();
    EXPECT_GT(out, 0) << solver;
    EXPECT_EQ(n.back(), n.front() + in - out) << solver;
  }
}

// The channel (an emitter with an inlet zone, an obstacle, an open end) with either solver: the
// same bytes at 1 and 2 threads, and the count is what came in less what left. PBF at 2 cm
// runs to 1.2 s, when water has left through the open face (at 1 m/s the front crosses the
// 1 m channel in 1 s); WCSPH, whose steps the sound speed sets, at its default 1 cm to 0.3 s
// (at 2 cm the 3 cm inflow is 1.5 spacings deep, too few: it blows up).
TEST(Channel, InflowOverTheBumpLeavesThroughTheOpenEndSameBitsAtOneAndTwoThreads) {
  for (const std::string solver : {"pbf", "wcsph"}) {
    const auto dir = pbf::test::temp_dir("channel-" + solver);
    const std::string run = solver == "pbf" ? " -v s=0.02 -v t_end=1.2 -v interval=0.4" : " -v t_end=0.3 -v interval=0.1";
    for (int t : {1, 2}) {
      auto r = run_engine("run " + scenario("channel.lua") + " -v solver=" + solver + run +
                          " -v restart_interval=0 --threads " + std::to_string(t) + " -v out=" +
                          (dir / std::to_string(t)).string());
      ASSERT_EQ(r.code, 0) << r.output;
      EXPECT_EQ(r.output.find("waits for room"), std::string::npos) << r.output;
    }
    const int compared = compare_outputs(dir / "1", dir / "2", solver);
    EXPECT_GE(compared, 5) << solver;  // four frames and the thermo CSV
    const auto thermo = pbf::test::read_csv(dir / "1" / "thermo.csv");
    const double in = thermo.at("in.count").back(), out = thermo.at("out.count").back();
    EXPECT_GT(in, 0) << solver;
    if (solver == "pbf") EXPECT_GT(out, 0) << solver;
    EXPECT_EQ(thermo.at("n").back(), in - out) << solver;
  }
}

// A yes/no variable (share/lua/flag.lua) takes true/false or 1/0; anything else stops the
// scenario with a message naming the variable, before the run.
TEST(ScenarioVariables, AYesNoVariableRefusesAnythingElseByName) {
  for (const std::string given : {"-v wall_density=maybe", "-v solver=wcsph -v fixed_dt=yes"}) {
    auto r = run_engine("run " + scenario("dambreak.lua") + " -v particles=1000 -v t_end=0.01 -v out= " + given);
    EXPECT_NE(r.code, 0) << given;
    const std::string name = given.substr(given.rfind("-v ") + 3, given.rfind('=') - given.rfind("-v ") - 3);
    EXPECT_NE(r.output.find("variable '" + name + "' must be true or false"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("Timing"), std::string::npos) << "no step should have run: " << r.output;
  }
  auto r = run_engine("run " + scenario("dambreak.lua") + " -v particles=1000 -v t_end=0.01 -v out= -v wall_density=0");
  EXPECT_EQ(r.code, 0) << r.output;
}

TEST(InitFile, RunsASceneFromTheGeneratorAtItsOutputInterval) {
  // The original study's workflow: write a scene file with share/make_scene.py, run it
  // with the standard pipeline, get one frame per output interval from t = 0 to the end.
  if (std::string(PBF_PYTHON).empty()) GTEST_SKIP() << "no python3";
  const auto dir = pbf::test::temp_dir("init-file");
  const std::string scene = (dir / "dambreak.txt").string();
  const std::string make = std::string(PBF_PYTHON) + " " + PBF_SOURCE_DIR + "/share/make_scene.py --kind dambreak " +
                           "--particles 2000 --interval 0.02 --t-final 0.1 -o " + scene + " 2>&1";
  ASSERT_EQ(std::system(make.c_str()), 0);
  auto r = run_engine("run " + scenario("init_file.lua") + " -v init=" + scene + " -v out=" + (dir / "frames").string());
  ASSERT_EQ(r.code, 0) << r.output;
  for (int k = 0; k <= 5; ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%05d.txt", k);
    EXPECT_TRUE(std::filesystem::exists(dir / "frames" / name)) << name;
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "frames" / "frame_00006.txt"));
  // Frame 0 is the file's own state, particle for particle.
  std::istringstream in(pbf::test::read_file(scene)), frame(pbf::test::read_file(dir / "frames" / "frame_00000.txt"));
  std::string line;
  int header = 0;
  while (header < 6 && std::getline(in, line))
    if (!line.empty() && line[0] != '#') ++header;
  std::getline(frame, line);  // N
  double a, b;
  int compared = 0;
  while (in >> a && frame >> b) {
    EXPECT_EQ(pbf::real(a), pbf::real(b));  // frames round-trip the particle data's type
    ++compared;
  }
  EXPECT_GT(compared, 6 * 1500);
}

TEST(Timing, TableNamesEveryStageAndFixAndTheNeighbourStatistics) {
  auto r = run_engine("run " + scenario("dambreak.lua") + " -v particles=1000 -v t_end=0.01 -v out=");
  ASSERT_EQ(r.code, 0) << r.output;
  for (const char* row : {"external_forces", "gravity (gravity)", "predict", "binning (candidates)",
                          "neighbour lists", "constraints", "pbf (pbf)", "walls (box)", "velocity_update",
                          "velocity_post", "vorticity (vorticity)", "xsph (xsph)", "end_of_step", "thermo",
                          "particle-steps per second", "neighbours per particle: mean"})
    EXPECT_NE(r.output.find(row), std::string::npos) << row;
}

// The first sloshing mode of scenarios/standing_wave.lua (0.4 m tank, 0.2 m deep, A = 5% of
// the depth, 10 mm spacing) with a kernel radius of 2.5 spacings keeps linear theory's period,
// omega^2 = g k tanh(k H), within 2% (measured -0.7%, 2026-11-26). With 2 spacings, the
// scenarios' usual radius, it runs 10% fast: the particle approximation of ~33 neighbours, an
// error that does not shrink at a fixed radius in spacings (docs/validation/standing_wave.md).
// The period: twice the mean time between the zero crossings of the difference of the water
// heights an eighth of the tank from each end, over three periods.
TEST(StandingWave, KeepsLinearTheorysPeriodWithAWideEnoughKernel) {
  const auto dir = pbf::test::temp_dir("standing-wave");
  auto r = run_engine("run " + scenario("standing_wave.lua") + " -v spacing=0.01 -v support=2.5 -v periods=3 -v csv=" +
                      (dir / "wave.csv").string());
  ASSERT_EQ(r.code, 0) << r.output;
  auto c = read_csv(dir / "wave.csv");
  const auto& t = c["time"];
  std::vector<double> crossings;
  for (std::size_t k = 1; k < t.size(); ++k) {
    const double d0 = c["in.left"][k - 1] - c["in.right"][k - 1], d1 = c["in.left"][k] - c["in.right"][k];
    if ((d0 > 0) != (d1 > 0)) crossings.push_back(t[k - 1] + (t[k] - t[k - 1]) * d0 / (d0 - d1));
  }
  ASSERT_GE(crossings.size(), 5u) << "the wave does not slosh";
  const double period = 2 * (crossings.back() - crossings.front()) / double(crossings.size() - 1);
  const double g = 9.81, k = M_PI / 0.4, theory = 2 * M_PI / std::sqrt(g * k * std::tanh(k * 0.2));
  EXPECT_NEAR(period / theory, 1.0, 0.02) << "period " << period << " s, linear theory " << theory << " s";
}

// The least-squares residual of d(t) = c + B exp(-gamma t) cos(omega t + phi) at (omega, gamma),
// c and the cosine's two parts solved linearly (share/validation/standing_wave.py's fit).
double damped_cosine_residual(const std::vector<double>& t, const std::vector<double>& d, double omega, double gamma) {
  double A[3][3] = {}, b[3] = {};
  for (std::size_t k = 0; k < t.size(); ++k) {
    const double e = std::exp(-gamma * t[k]), f[3] = {1, e * std::cos(omega * t[k]), e * std::sin(omega * t[k])};
    for (int i = 0; i < 3; ++i) {
      b[i] += f[i] * d[k];
      for (int j = 0; j < 3; ++j) A[i][j] += f[i] * f[j];
    }
  }
  auto det = [](const double m[3][3]) {
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  };
  const double whole = det(A);
  double x[3];
  for (int c = 0; c < 3; ++c) {  // Cramer's rule
    double m[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) m[i][j] = j == c ? b[i] : A[i][j];
    x[c] = det(m) / whole;
  }
  double sum = 0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    const double e = std::exp(-gamma * t[k]);
    const double r = d[k] - x[0] - x[1] * e * std::cos(omega * t[k]) - x[2] * e * std::sin(omega * t[k]);
    sum += r * r;
  }
  return sum;
}

// DFSPH keeps the standing wave's height (issue 34: at least 0.9 of it a period at 10 mm, where
// PBF keeps 0.65 and WCSPH 0.75): the scene's defaults under -v solver=dfsph (nu = 1e-4, whose
// own decay is 1% a period), four periods, d = in.left - in.right fitted as standing_wave.py
// does (a grid over omega and gamma, then a pattern search). Measured 2026-11-29: 0.948 (float),
// 0.935 (double).
TEST(StandingWave, DfsphKeepsNineTenthsOfItsHeightAPeriod) {
  const auto dir = pbf::test::temp_dir("standing-wave-dfsph");
  auto r = run_engine("run " + scenario("standing_wave.lua") + " -v spacing=0.01 -v support=2.5 -v periods=4 " +
                      "-v solver=dfsph -v csv=" + (dir / "wave.csv").string());
  ASSERT_EQ(r.code, 0) << r.output;
  auto c = read_csv(dir / "wave.csv");
  const std::vector<double>& t = c["time"];
  std::vector<double> d(t.size());
  for (std::size_t k = 0; k < t.size(); ++k) d[k] = c["in.left"][k] - c["in.right"][k];
  const double g = 9.81, k = M_PI / 0.4, omega0 = std::sqrt(g * k * std::tanh(k * 0.2));
  double best = std::numeric_limits<double>::infinity(), omega = omega0, gamma = 0;
  for (int a = 0; a <= 100; ++a)
    for (int b = 0; b <= 25; ++b) {
      const double w = omega0 * (0.5 + a / 100.0), y = omega0 / 2 * b / 25.0;
      const double res = damped_cosine_residual(t, d, w, y);
      if (res < best) best = res, omega = w, gamma = y;
    }
  for (double step_w = omega0 / 200, step_g = omega0 / 100; step_w > 1e-6 * omega0;) {
    bool moved = false;
    for (const auto& [dw, dg] : {std::pair{step_w, 0.0}, {-step_w, 0.0}, {0.0, step_g}, {0.0, -step_g}}) {
      const double w = omega + dw, y = std::max(0.0, gamma + dg), res = damped_cosine_residual(t, d, w, y);
      if (res < best) best = res, omega = w, gamma = y, moved = true;
    }
    if (!moved) step_w /= 2, step_g /= 2;
  }
  EXPECT_GE(std::exp(-gamma * 2 * M_PI / omega), 0.9) << "period " << 2 * M_PI / omega << " s";
}

// Floating bodies (scenarios/floating.lua, with its two bodies on joints) with either solver:
// the same bytes (the bodies' poses in thermo.csv, and a picture) at 1 and 2 threads; in the
// PBF run, which reaches the bodies' landing (released at 0.3 s from up to 0.15 m above the
// water: in it by 0.5 s), the stone lies on the floor a spacing up, the wooden plank and the
// buoy on its slider float, their centres within a spacing of the water's level (0.2 m, less
// the PBF column's compression of a few mm), and the ball on its joint hangs no lower than its
// arm of 0.11 m reaches.
TEST(Floating, BodiesFallIntoTheTankSameBitsAtOneAndTwoThreads) {
  for (const std::string solver : {"pbf", "wcsph"}) {
    const auto dir = pbf::test::temp_dir("floating-" + solver);
    const std::string t_end = solver == "pbf" ? "1.2" : "0.35";
    for (int t : {1, 2}) {
      auto r = run_engine("run " + scenario("floating.lua") + " -v joints=true -v solver=" + solver +
                          " -v particles=4000 -v t_end=" +
                          t_end + " -v images=0.3 --threads " + std::to_string(t) + " -v out=" +
                          (dir / std::to_string(t)).string());
      ASSERT_EQ(r.code, 0) << r.output;
    }
    const int compared = compare_outputs(dir / "1", dir / "2", solver);
    EXPECT_GE(compared, 2) << solver;  // the thermo CSV and a picture
    if (solver != "pbf") continue;
    const auto thermo = pbf::test::read_csv(dir / "1" / "thermo.csv");
    const double spacing = 0.4 / std::floor(0.4 / std::cbrt(0.6 * 0.4 * 0.2 / 4000) + 0.5);
    EXPECT_NEAR(thermo.at("stone.z").back(), 0.03 + spacing, 0.05 * spacing);
    EXPECT_NEAR(thermo.at("plank.z").back(), 0.2, spacing);
    EXPECT_NEAR(thermo.at("buoy.z").back(), 0.2, spacing);
    for (double z : thermo.at("lamp.z")) EXPECT_GE(z, 0.3 - 0.11 - 1e-9);
  }
}
