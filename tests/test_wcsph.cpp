// Weakly compressible SPH, composed from the same pipeline as PBF: a column at rest carries
// the hydrostatic pressure, the dam break's front follows the PBF run's, the CFL control
// keeps its bound, a time step far too large is stopped with a clear message before it
// writes garbage, and a restart continues a WCSPH run exactly.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <map>
#include <sstream>

#include <random>

#include "engine/sph/lattice.hpp"
#include "engine/core/simulation.hpp"
#include "engine/registry/style_registry.hpp"
#include "test_util.hpp"

using pbf::test::read_file;
using pbf::test::run_engine;
using pbf::test::scenario;
using pbf::test::read_csv;
using pbf::test::temp_dir;
using pbf::test::write_file;

namespace {

const std::string kShare = std::string(PBF_SOURCE_DIR) + "/share";

// Lines 1-10: a column of water H high on an H/2 square floor (2000 particles at spacing
// s = H/10, h = 2s), gravity, the WCSPH pipeline of share/lua/solvers.lua, box walls.
const std::string kColumn =
    "package.path = var.share .. '/lua/?.lua;' .. package.path\n"
    "local H, s = 0.2, 0.01\n"
    "pbf.domain{lo = {0, 0, 0}, hi = {H / 2, H / 2, 1.5 * H}}\n"
    "pbf.kernel_radius(2 * s)\n"
    "pbf.timestep(var.dt or 0.4 * 2 * s / math.sqrt(2 * 9.81 * H))\n"
    "pbf.lattice{lo = {0, 0, 0}, hi = {H / 2, H / 2, H}, spacing = s}\n"
    "pbf.fix('gravity', 'gravity', {})\n"
    "require('solvers').wcsph{fixed_dt = var.fixed_dt, density = var.density, diffusion = var.diffusion,\n"
    "                          negative_pressure = var.negative_pressure}\n"
    "pbf.fix('walls', 'box', {})\n";

using pbf::test::read_frame_rows;

// Runs the column (kColumn) followed by `rest` of a script in `dir`, with -v extra variables.
pbf::test::Result run_column(const std::filesystem::path& dir, const std::string& rest, const std::string& vars = "") {
  write_file(dir / "a.lua", kColumn + rest);
  return run_engine("run " + (dir / "a.lua").string() + " -v share=" + kShare + " -v dir=" + dir.string() + vars);
}


TEST(Wcsph, ColumnAtRestCarriesTheHydrostaticPressure) {
  const auto dir = temp_dir("wcsph-column");
  // 0.6 s for the initial transient (the column settles from zero pressure, and the
  // acoustic waves it starts, period 4H/c0 = 0.04 s, are damped by the artificial
  // viscosity), then pressures averaged over the frames of 0.4 s, one every 0.02 s.
  auto r = run_column(dir, "pbf.run_until(0.6)\n"
                           "pbf.fix('p', 'dump/text', {path = var.dir .. '/p_*.txt', interval = 0.02,\n"
                           "  fields = {'position', 'pressure'}})\npbf.run_until(1.0)\n");
  ASSERT_EQ(r.code, 0) << r.output;
  const double H = 0.2, s = 0.01, h = 0.02, rho0 = 1000, g = 9.81;
  // Bands 2 cm thick (two layers of particles: the column at rest keeps its lattice, whose
  // layers alternate by about 10% in pressure, docs/physics.md "Known limits of WCSPH");
  // pressure against depth below the free surface, half a spacing above the top particles.
  std::vector<double> sum(30, 0), count(30, 0);
  double top = 0;
  int frames = 0;
  for (int f = 0;; ++f) {
    const auto path = dir / fmt::format("p_{:05d}.txt", f);
    if (!std::filesystem::exists(path)) break;
    const auto rows = read_frame_rows(path);
    ASSERT_EQ(rows.size(), 2000u) << "a particle was lost";
    double frame_top = 0;
    for (const auto& row : rows) {
      ASSERT_EQ(row.size(), 4u);
      frame_top = std::max(frame_top, row[2]);
      const int layer = static_cast<int>(row[2] / 0.02);
      sum.at(layer) += row[3];
      count.at(layer) += 1;
    }
    // The top layer rests at H - s/2; a particle h above H has no neighbour left: it was thrown off.
    EXPECT_LT(frame_top, H + h) << "frame " << f << ": a particle left the surface";
    top += frame_top;
    ++frames;
  }
  ASSERT_GE(frames, 20);  // 21 unless the last falls just after 1.0 s (frames count from the dump's start)
  const double surface = top / frames + s / 2, scale = rho0 * g * surface;
  // Bound: 16% of the floor pressure. Measured: 10-12% (5-6% when the density was summed
  // with poly6, whose pressure force was not conservative). The SPH pressure gradient with a
  // support of two spacings is not exact (the layers are not a lattice after the transient),
  // so the column settles with a steeper pressure gradient than rho0 g (docs/physics.md,
  // "Known limits of WCSPH"); averaging 20 frames leaves about 1% of acoustic noise.
  int checked = 0;
  for (int layer = 0; layer < 30; ++layer) {
    const double z = (layer + 0.5) * 0.02;
    if (count[layer] == 0 || z < h || z > surface - h) continue;
    const double expected = rho0 * g * (surface - z), measured = sum[layer] / count[layer];
    EXPECT_NEAR(measured, expected, 0.16 * scale) << "layer at z = " << z;
    ++checked;
  }
  EXPECT_GE(checked, 7);
}

// Z = front / a at T = t sqrt(2 g / a), interpolated from a thermo CSV.
double front_at(const std::map<std::string, std::vector<double>>& csv, double T) {
  const double a = 0.1, t = T / std::sqrt(2 * 9.81 / a);
  const auto& time = csv.at("time");
  const auto& front = csv.at("front");
  for (std::size_t k = 1; k < time.size(); ++k)
    if (time[k] >= t) return (front[k - 1] + (front[k] - front[k - 1]) * (t - time[k - 1]) / (time[k] - time[k - 1])) / a;
  return NAN;
}

TEST(Wcsph, DamBreakFrontFollowsThePbfRunUntilTEquals2) {
  const auto dir = temp_dir("wcsph-dambreak");
  std::map<std::string, std::vector<double>> csv[2];
  const char* scenarios[2] = {"dambreak.lua", "dambreak_wcsph.lua"};
  for (int k = 0; k < 2; ++k) {
    const auto out = dir / std::to_string(k);
    auto r = run_engine(fmt::format("run {} -v particles=2000 -v t_end=0.17 -v out={} -v restart_interval=0 "
                                    "-v interval=1",
                                    scenario(scenarios[k]), out.string()));
    ASSERT_EQ(r.code, 0) << r.output;
    csv[k] = read_csv(out / "thermo.csv");
  }
  // Measured: within 2% at T = 0.5 to 2 (2028 particles). Allowed: 5%, "a few percent": both
  // approximate one incompressible flow, PBF leaving about 3% compression at 4 iterations and
  // WCSPH Ma^2 = 1% at Mach 0.1, which change the column's volume and front by a few percent; a
  // WCSPH pressure or viscosity off by a factor moves its front by far more.
  for (double T : {0.5, 1.0, 1.5, 2.0}) {
    const double pbf = front_at(csv[0], T), wcsph = front_at(csv[1], T);
    EXPECT_NEAR(wcsph, pbf, 0.05 * pbf) << "T = " << T;
  }
  // The WCSPH steps were chosen by the CFL control: far below PBF's. Its bound 0.15 h / c0 with
  // c0 = 10 sqrt(2 g 2a), against PBF's 0.4 h / sqrt(2 g 2a), is 0.0375 of it.
  EXPECT_LT(csv[1].at("dt").back(), 0.1 * csv[0].at("dt").back());
}

TEST(Wcsph, CflStepNeverExceedsItsBound) {
  const auto dir = temp_dir("wcsph-cfl");
  auto r = run_column(dir, "pbf.compute('v', 'speed')\n"
                           "pbf.thermo{every = 1, csv = var.dir .. '/t.csv', columns = {'step', 'dt', "
                           "'v.max'}}\npbf.run(400)\n");
  ASSERT_EQ(r.code, 0) << r.output;
  const auto csv = read_csv(dir / "t.csv");
  // The bound it claims: min(max_dt, 0.15 h / (c0 + |v|max), ...), c0 = 10 sqrt(2 g H)
  // (the lattice's z extent plus one spacing is H), max_dt the script's time step.
  const double h = 0.02, c0 = 10 * std::sqrt(2 * 9.81 * 0.2), max_dt = 0.4 * h / std::sqrt(2 * 9.81 * 0.2);
  ASSERT_EQ(csv.at("dt").size(), 401u);
  for (std::size_t k = 0; k < csv.at("dt").size(); ++k) {
    const double bound = std::min(max_dt, 0.15 * h / (c0 + csv.at("v.max")[k]));
    // Within rounding: the engine measures H from positions in the data's precision.
    EXPECT_LE(csv.at("dt")[k], bound * (1 + pbf::test::kRounding)) << "step " << csv.at("step")[k];
  }
  EXPECT_LT(csv.at("dt")[200], 0.2 * max_dt);  // the bound is 0.15 h / c0 = 0.0375 max_dt: the control acts
}

TEST(Wcsph, ATimeStepFarTooLargeIsStoppedBeforeGarbageFrames) {
  const auto dir = temp_dir("wcsph-dt");
  // 40 times the CFL step, fixed.
  auto r = run_column(dir, "pbf.fix('f', 'dump/text', {path = var.dir .. '/f_*.txt', every = 1})\n"
                           "pbf.run(1000)\n",
                      " -v fixed_dt=true -v dt=0.006");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.output.find("the time step 0.006 s is beyond WCSPH's stable limit h / c0"), std::string::npos)
      << r.output;
  // Every frame written holds finite values and no compression past the limit.
  int frames = 0;
  for (int f = 0;; ++f) {
    const auto path = dir / fmt::format("f_{:05d}.txt", f);
    if (!std::filesystem::exists(path)) break;
    for (const auto& row : read_frame_rows(path))
      for (double v : row) ASSERT_TRUE(std::isfinite(v)) << path;
    ++frames;
  }
  EXPECT_GE(frames, 1);
  EXPECT_LT(frames, 1000);
}

TEST(Wcsph, RestartContinuesExactly) {
  const auto dir = temp_dir("wcsph-restart");
  write_file(dir / "wrap.lua", "dofile(var.scenario)\npbf.write_restart(var.final)\n");
  auto args = [&](const std::string& final, int threads) {
    return fmt::format("run {} -v scenario={} -v particles=1000 -v t_end=0.01 -v restart_every=40 -v out={} "
                       "-v final={} --threads {}",
                       (dir / "wrap.lua").string(), scenario("dambreak_wcsph.lua"), (dir / "out").string(),
                       (dir / final).string(), threads);
  };
  auto r = run_engine(args("straight", 1));
  ASSERT_EQ(r.code, 0) << r.output;
  std::filesystem::copy_file(dir / "out" / "restart.40.restart", dir / "r40");
  r = run_engine(args("continued", 2) + " -v restart=" + (dir / "r40").string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(r.output.find("warning"), std::string::npos) << r.output;
  EXPECT_TRUE(read_file(dir / "straight") == read_file(dir / "continued"));
}

}  // namespace

namespace {

// A block of 512 particles with random velocities in empty space, only viscosity acting:
// the pairwise forces conserve momentum to rounding, and kinetic energy only falls.
TEST(Wcsph, ViscositiesConserveMomentumAndDissipateEnergy) {
  for (const char* kind : {"artificial", "laplacian"}) {
    pbf::Simulation sim;
    pbf::Domain d;
    for (int a = 0; a < 3; ++a) d.lo[a] = -1, d.hi[a] = 1;
    sim.set_domain(d);
    sim.set_kernel_radius(0.02);
    sim.set_timestep(1e-4);
    const double lo[3] = {-0.04, -0.04, -0.04}, hi[3] = {0.04, 0.04, 0.04}, v0[3] = {0, 0, 0};
    pbf::add_lattice(sim, lo, hi, 0.01, v0);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-0.5, 0.5);
    auto& P = sim.particles();
    for (std::size_t i = 0; i < P.size(); ++i) P.vx()[i] = u(rng), P.vy()[i] = u(rng), P.vz()[i] = u(rng);
    const auto& styles = pbf::StyleRegistry::builtin();
    sim.add_fix(styles.make_fix("integrator", "leapfrog", {}));
    sim.add_fix(styles.make_fix("viscosity", "sph_viscosity",
                                {{"kind", std::string(kind)}, {"nu", 1e-3}, {"alpha", 0.5}, {"sound_speed", 10.0}}));
    auto momentum_energy = [&](double out[4]) {
      out[0] = out[1] = out[2] = out[3] = 0;
      for (std::size_t i = 0; i < P.size(); ++i) {
        const double m = P.mass()[i], v[3] = {P.vx()[i], P.vy()[i], P.vz()[i]};
        for (int c = 0; c < 3; ++c) out[c] += m * v[c];
        out[3] += 0.5 * m * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
      }
    };
    double before[4], after[4];
    momentum_energy(before);
    double energy = before[3];
    for (int k = 0; k < 10; ++k) {
      sim.run(5);
      momentum_energy(after);
      EXPECT_LT(after[3], energy) << kind << ": kinetic energy rose";
      energy = after[3];
    }
    // Pair forces are antisymmetric: momentum moves only by the rounding of 50 steps' sums, far
    // inside 100 kRounding of one random walk's |p|; one force without its partner is O(|p|).
    const double scale = std::sqrt(2 * before[3] * 512 * P.mass()[0]);  // |p| of one random walk
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(after[c], before[c], 100 * pbf::test::kRounding * scale) << kind;
    // The random field's energy is at the lattice's scale, k ~ pi/s, where even the Laplacian's
    // nu k^2 = 99/s takes half of it in the 5 ms (e^(-2 nu k^2 t)); a viscosity doing nothing keeps all.
    EXPECT_LT(after[3], 0.99 * before[3]) << kind << ": no dissipation";
  }
}

}  // namespace

namespace {

// The original study's scene file run by WCSPH: the file's time step is an upper bound, the
// CFL control takes smaller steps, and steps end exactly on the output interval, so frame k
// is the state at k times the interval.
TEST(Wcsph, SceneFileRunsWithSubStepsAndFramesOnTheInterval) {
  if (std::string(PBF_PYTHON).empty()) GTEST_SKIP() << "no python3";
  const auto dir = temp_dir("wcsph-init");
  const std::string scene = (dir / "dambreak.txt").string();
  const std::string make = std::string(PBF_PYTHON) + " " + PBF_SOURCE_DIR + "/share/make_scene.py --kind dambreak " +
                           "--particles 2000 --interval 0.02 --t-final 0.1 -o " + scene + " 2>&1";
  ASSERT_EQ(std::system(make.c_str()), 0);
  // Record every step's time, then check the interval's multiples are among them.
  write_file(dir / "wrap.lua",
             "local times = {}\nlocal run_until = pbf.run_until\n"
             "pbf.run_until = function(t)\n"
             "  pbf.every('clock', 1, function(step, time) times[#times + 1] = time end)\n"
             "  run_until(t)\n"
             "  local hit = 0\n"
             "  for k = 1, 5 do for _, time in ipairs(times) do\n"
             "    if math.abs(time - 0.02 * k) < 1e-12 then hit = hit + 1; break end end end\n"
             "  print(string.format('STEPS %d HIT %d', #times, hit))\nend\n"
             "dofile(var.scenario)\n");
  auto r = run_engine("run " + (dir / "wrap.lua").string() + " -v scenario=" + scenario("init_file.lua") +
                      " -v init=" + scene + " -v out=" + (dir / "frames").string() + " -v solver=wcsph");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("HIT 5"), std::string::npos) << r.output;
  const auto at = r.output.find("STEPS ");
  ASSERT_NE(at, std::string::npos);
  // The file's dt takes 50 steps to 0.1 s; cfl's bound 0.15 h / c0 is several times shorter.
  EXPECT_GT(std::stoi(r.output.substr(at + 6)), 50 * 2) << "no sub-steps below the file's dt = 0.002 s";
  for (int k = 0; k <= 5; ++k)
    EXPECT_TRUE(std::filesystem::exists(dir / "frames" / fmt::format("frame_{:05d}.txt", k))) << k;
  EXPECT_FALSE(std::filesystem::exists(dir / "frames" / "frame_00006.txt"));
}

}  // namespace

namespace {

// Density by the continuity equation: the column stays at rest. Bound: mean speed under 5%
// of sqrt(2 g H) = 2.0 m/s after 0.5 s (measured about 1.5-2%; a collapse or a slosh moves the
// whole column at a good share of it), the top layer's centres within two spacings of their
// start, H - s/2 = 0.195 m (the settling is under a spacing, docs/physics.md).
TEST(Wcsph, ContinuityDensityKeepsAColumnAtRest) {
  const auto dir = temp_dir("wcsph-continuity");
  auto r = run_column(dir, "pbf.compute('v', 'speed')\npbf.compute('top', 'front', {axis = 'z', "
                           "percentile = 99})\npbf.thermo{every = 500, csv = var.dir .. '/t.csv', "
                           "columns = {'time', 'v.avg', 'top'}}\npbf.run_until(0.5)\n",
                      " -v density=continuity");
  ASSERT_EQ(r.code, 0) << r.output;
  const auto csv = read_csv(dir / "t.csv");
  EXPECT_LT(csv.at("v.avg").back(), 0.05 * std::sqrt(2 * 9.81 * 0.2));
  EXPECT_NEAR(csv.at("top").back(), 0.195, 0.02);
}

// Density diffusion (delta-SPH with the hydrostatic part left out): the continuity equation
// starts the column at rest density, and the sound waves of that start (period 4 H / c0 =
// 0.04 s) still make the pressure swing by 10-30% of rho0 g H after 2 s without diffusion
// (measured); with delta = 0.1 they are gone and the pressure is hydrostatic. Bound: below
// two spacings from the surface, over 0.1 s of frames, the pressure within 8% of rho0 g H (RMS)
// of rho0 g depth (measured 4-5%), where no diffusion misses it; the column keeps its height
// within a spacing (the hydrostatic part is not diffused away).
TEST(Wcsph, DensityDiffusionDampsTheSoundOfAContinuityStart) {
  for (const std::string delta : {"0", "0.1"}) {
    const auto dir = temp_dir("wcsph-diffusion-" + delta);
    auto r = run_column(dir, "pbf.run_until(2)\n"
                             "pbf.fix('p', 'dump/text', {path = var.dir .. '/p_*.txt', interval = 0.01,\n"
                             "  fields = {'position', 'pressure'}})\npbf.run_until(2.1)\n",
                        " -v density=continuity -v diffusion=" + delta + " --threads 1");  // one core: ctest runs two tests at once
    ASSERT_EQ(r.code, 0) << r.output;
    const double H = 0.2, s = 0.01, rho0 = 1000, g = 9.81;
    double sum2 = 0, top_sum = 0;
    int count = 0, frames = 0;
    for (int f = 0;; ++f) {
      const auto path = dir / fmt::format("p_{:05d}.txt", f);
      if (!std::filesystem::exists(path)) break;
      const auto rows = read_frame_rows(path);
      std::vector<double> heights;
      for (const auto& row : rows) heights.push_back(row[2]);
      std::sort(heights.begin(), heights.end());
      const double top = heights[heights.size() * 99 / 100] + s / 2;  // the free surface
      for (const auto& row : rows) {
        const double depth = top - row[2];
        if (depth < 2 * s) continue;
        sum2 += std::pow(row[3] - rho0 * g * depth, 2);
        ++count;
      }
      top_sum += top;
      ++frames;
    }
    ASSERT_GE(frames, 10) << r.output;  // every 0.01 s over 0.1 s (the last may fall past the end)
    const double rms = std::sqrt(sum2 / count) / (rho0 * g * H);
    if (delta == "0") {
      EXPECT_GT(rms, 0.08) << "without diffusion the start's sound waves should still ring at 2 s";
    } else {
      EXPECT_LT(rms, 0.08);
      EXPECT_NEAR(top_sum / frames, H, s);
    }
  }
}

// The parameter belongs to the continuity equation: asked of the summation, it is refused by name.
TEST(Wcsph, DiffusionWithTheSummedDensityIsRefused) {
  const auto dir = temp_dir("wcsph-diffusion-summation");
  auto r = run_column(dir, "pbf.run_until(0.01)\n", " -v density=summation -v diffusion=0.1");
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("'diffusion'"), std::string::npos) << r.output;
}

// solvers.lua passes `negative_pressure` through, "true" and "false" from -v as booleans: the
// column's summed density is short of rho0 within h of its free surface from the first step,
// so kept pressures go negative there and clamped ones do not.
TEST(Wcsph, NegativePressureFromTheCommandLine) {
  for (const std::string keep : {"true", "false"}) {
    const auto dir = temp_dir("wcsph-negative-" + keep);
    auto r = run_column(dir, "pbf.run(2)\n"
                             "pbf.fix('p', 'dump/text', {path = var.dir .. '/p_*.txt', interval = 1,\n"
                             "  fields = {'pressure'}})\npbf.run(1)\n",
                        " -v density=summation -v negative_pressure=" + keep);
    ASSERT_EQ(r.code, 0) << r.output;
    double lowest = 0;
    for (const auto& row : read_frame_rows(dir / "p_00000.txt")) lowest = std::min(lowest, row[0]);
    // Tait's B = rho0 c0^2 / 7 is 59 kPa here: 1% short of rho0 is -4 kPa; -10 Pa asks for the sign.
    if (keep == "true") EXPECT_LT(lowest, -10.0) << "a surface short of rho0 keeps its negative pressure";
    else EXPECT_EQ(lowest, 0.0);
  }
}

// `density` and `density_error` are the density the solver uses; the SPH sum has its own
// name. Under the continuity density the two differ; under the summation they agree, and
// frame 0 (before any step) holds the summed density, not an empty field. (The sum is taken
// before the walls' projection moves the particles at the contact distance: those and their
// neighbours, within h plus half a spacing of a face, are not compared.)
TEST(Wcsph, DensityColumnsAreTheSolversDensity) {
  for (const std::string density : {"continuity", "summation"}) {
    const auto dir = temp_dir("wcsph-density");
    auto r = run_column(dir, "pbf.fix('f', 'dump/text', {path = var.dir .. '/f_*.txt', every = 100, fields = {'id', "
                             "'density', 'density_error', 'summed_density', 'position'}})\npbf.run(200)\n",
                        " -v fixed_dt=true -v dt=0.0002 -v density=" + density);
    ASSERT_EQ(r.code, 0) << r.output;
    for (const char* frame : {"f_00000.txt", "f_00002.txt"}) {
      const auto rows = read_frame_rows(dir / frame);
      ASSERT_EQ(rows.size(), 2000u);
      std::vector<double> difference;  // |rho - rho_summed| / rho0
      for (const auto& row : rows) {
        ASSERT_EQ(row.size(), 7u);
        EXPECT_NEAR(row[2], row[1] / 1000 - 1, 1e-12 + pbf::test::kRounding) << frame << " particle " << row[0];
        const double x = row[4], y = row[5], z = row[6], clear = 0.02 + 0.005;
        if (density == "summation" && std::min({x, y, z, 0.1 - x, 0.1 - y}) < clear) continue;
        difference.push_back(std::fabs(row[1] - row[3]) / 1000);
      }
      std::sort(difference.begin(), difference.end());
      const bool start = std::string(frame) == "f_00000.txt";
      if (density == "summation") {  // the field is the sum at the step's positions
        EXPECT_LE(difference.back(), pbf::test::kRounding) << frame;
      } else if (!start) {
        // The integrated density stays near rho0 where the sum falls at the free surface
        // (a surface particle misses up to half its kernel: above 5%, below 50%); inside, the
        // two agree to a percent (the median), as both describe one nearly incompressible state.
        EXPECT_GT(difference.back(), 0.05) << frame;
        EXPECT_LT(difference.back(), 0.5) << frame;
        EXPECT_LT(difference[difference.size() / 2], 0.01) << frame;
      } else {  // the continuity equation starts at rest density, the sum at a lattice's own
        for (const auto& row : rows) EXPECT_DOUBLE_EQ(row[1], 1000.0);
      }
    }
  }
}

TEST(Wcsph, PipelinesThatCannotWorkAreErrors) {
  const auto dir = temp_dir("wcsph-pipeline");
  const std::string scene =
      "pbf.domain{lo = {0, 0, 0}, hi = {0.2, 0.2, 0.2}}; pbf.kernel_radius(0.02); pbf.timestep(0.001)\n"
      "pbf.lattice{lo = {0.05, 0.05, 0.05}, hi = {0.1, 0.1, 0.1}, spacing = 0.01}\n";
  write_file(dir / "a.lua", scene + "pbf.fix('w', 'wcsph', {})\npbf.run(1)\n");
  auto r = run_engine("run " + (dir / "a.lua").string());
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.output.find(":4: fix 'w' (wcsph): wcsph adds accelerations, but no fix integrates them"),
            std::string::npos)
      << r.output;
  write_file(dir / "b.lua", scene + "pbf.fix('i', 'leapfrog', {})\npbf.fix('p', 'pbf', {})\npbf.run(1)\n");
  r = run_engine("run " + (dir / "b.lua").string());
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.output.find(":4: fix 'p' (pbf): fix 'i' (leapfrog) does the time integration already"),
            std::string::npos)
      << r.output;
  write_file(dir / "c.lua", scene + "pbf.fix('p', 'pbf', {})\npbf.fix('w', 'wcsph', {})\npbf.run(1)\n");
  r = run_engine("run " + (dir / "c.lua").string());
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.output.find(":5: fix 'w' (wcsph): wcsph adds accelerations, but no fix integrates them (fix 'p' (pbf) "
                          "moves positions itself"),
            std::string::npos)
      << r.output;
}

}  // namespace

// A wall that moves into the fluid at 0.2 m/s, with the fluid next to it carried along: the
// continuity equation must see the fluid approach the wall at its velocity relative to the
// wall. The fluid is weakly compressible (Mach 0.014; the impulsive start's water hammer is
// rho0 c0 U, 1.4% of rho0 in density, the hydrostatic part 0.5%), so near the wall and below
// the free surface its density stays within 2% of rho0. (Counting the fluid's own velocity
// against the wall, the density there fell by 90% in 0.06 s.)
TEST(Wcsph, TheContinuityDensitySeesAMovingWallsVelocity) {
  const auto dir = temp_dir("wcsph-moving-wall");
  write_file(dir / "piston.lua",
             "pbf.domain{lo = {0, 0, 0}, hi = {0.3, 0.06, 0.15}}\npbf.kernel_radius(0.02)\npbf.timestep(0.0001)\n"
             "pbf.lattice{lo = {0.05, 0, 0}, hi = {0.25, 0.06, 0.1}, spacing = 0.01}\n"
             "pbf.fix('paddle', 'solid', {shape = 'box', lo = {-0.1, -0.02, -0.02}, hi = {0.05, 0.08, 0.17},\n"
             "  motion = function(t) return {translate = {0.2 * t, 0, 0}} end})\n"
             "pbf.fix('walls', 'box', {})\npbf.fix('gravity', 'gravity', {})\npbf.fix('integrator', 'leapfrog', {})\n"
             "pbf.fix('wcsph', 'wcsph', {density = 'continuity'})\npbf.fix('viscosity', 'sph_viscosity', {})\n"
             "pbf.fix('d', 'dump/text', {path = var.dir .. '/d_*.txt', interval = 0.06, fields = {'position', 'density'}})\n"
             "pbf.run_until(0.06)\n");
  auto r = run_engine("run " + (dir / "piston.lua").string() + " -v dir=" + dir.string() + " --threads 1");
  ASSERT_EQ(r.code, 0) << r.output;
  const double face = 0.05 + 0.2 * 0.06, h = 0.02;
  int near = 0;
  for (const auto& row : read_frame_rows(dir / "d_00001.txt")) {
    if (row[0] > face + 2 * h || row[2] > 0.06) continue;
    ++near;
    EXPECT_NEAR(row[3] / 1000, 1.0, 0.02) << "at x = " << row[0] << ", z = " << row[2];
  }
  EXPECT_GT(near, 100);
}

// The equation of state: after a step, every particle's pressure is the Tait equation of its
// density, p = B ((rho/rho0)^gamma - 1), B = rho0 c0^2 / gamma, negative values clamped to 0.
// A block of 8^3 particles whose masses are 3% above the lattice's (rho = 1.03 rho0 inside,
// where p = 0.23 B; less at its surface, where the clamp acts). Both the density and the
// pressure are the fix's fields. Rounding of the single-precision evaluation: the ratio
// rho/rho0 (u), the power (gamma u and pow's own ulp), B (u), so at most
// B u ((gamma + 4) x^gamma + 2 |x^gamma - 1|), x = rho/rho0: 3e-6 of p here. An exponent off by
// one (x^6 - 1 = 0.19 instead of 0.23) misses by 16%.
TEST(Wcsph, ThePressureIsTheTaitEquationOfTheDensity) {
  for (const double gamma : {7.0, 3.0}) {
    pbf::Simulation sim;
    sim.set_domain(pbf::Domain{{0, 0, 0}, {0.2, 0.2, 0.2}});
    sim.set_kernel_radius(0.02);
    sim.set_timestep(1e-4);
    const double lo[3] = {0.06, 0.06, 0.06}, hi[3] = {0.14, 0.14, 0.14}, v[3] = {0, 0, 0};
    pbf::add_lattice(sim, lo, hi, 0.01, v);
    auto& P = sim.particles();
    for (std::size_t i = 0; i < P.size(); ++i) P.mass()[i] *= pbf::real(1.03);
    const double c0 = 20, rho0 = sim.rest_density(), B = rho0 * c0 * c0 / gamma;
    const auto& styles = pbf::StyleRegistry::builtin();
    sim.add_fix(styles.make_fix("integrator", "leapfrog", {}));
    sim.add_fix(styles.make_fix("wcsph", "wcsph", {{"sound_speed", c0}, {"gamma", gamma}}));
    sim.run(1);
    const pbf::real* rho = P.data(*P.find("density"));
    const pbf::real* p = P.data(*P.find("pressure"));
    int compressed = 0;
    for (std::size_t i = 0; i < P.size(); ++i) {
      const double x = double(rho[i]) / rho0, power = std::pow(x, gamma);
      const double expected = std::max(0.0, B * (power - 1));
      const double bound = B * pbf::test::kUnitRoundoff * ((gamma + 4) * power + 2 * std::fabs(power - 1));
      ASSERT_NEAR(p[i], expected, bound) << "particle " << P.ids()[i] << ", rho = " << rho[i] << ", gamma " << gamma;
      if (x > 1.029) ++compressed;
    }
    EXPECT_GE(compressed, 4 * 4 * 4);  // the inner particles, 2 spacings (h) from the surface
  }
}

// cfl's viscous limit: with the Laplacian viscosity's nu the step is at most
// 0.125 (h/2)^2 / nu (Morris et al. 1997, h/2 the smoothing length). A block at rest, no
// gravity, sound speed 1 m/s (Courant bound 0.15 h / c0 = 3 ms) and nu = 0.01 m^2/s (viscous
// bound 1.25 ms): the viscous one decides, to rounding; with the artificial form instead it
// does not apply, and the Courant bound decides.
TEST(Wcsph, CflKeepsTheStepUnderTheViscousLimit) {
  for (const std::string kind : {"laplacian", "artificial"}) {
    pbf::Simulation sim;
    sim.set_domain(pbf::Domain{{0, 0, 0}, {0.2, 0.2, 0.2}});
    sim.set_kernel_radius(0.02);
    sim.set_timestep(0.01);
    const double lo[3] = {0.06, 0.06, 0.06}, hi[3] = {0.14, 0.14, 0.14}, v[3] = {0, 0, 0};
    pbf::add_lattice(sim, lo, hi, 0.01, v);
    const auto& styles = pbf::StyleRegistry::builtin();
    sim.add_fix(styles.make_fix("integrator", "leapfrog", {}));
    sim.add_fix(styles.make_fix("wcsph", "wcsph", {{"sound_speed", 1.0}}));
    sim.add_fix(styles.make_fix("viscosity", "sph_viscosity", {{"kind", kind}, {"nu", 0.01}}));
    sim.add_fix(styles.make_fix("cfl", "cfl", {}));
    sim.run(1);
    // The Courant bound with the speed the first step gave (the block's surface starts to move).
    const auto& P = sim.particles();
    double fastest = 0;
    for (std::size_t i = 0; i < P.size(); ++i)
      fastest = std::max(fastest, std::sqrt(double(P.vx()[i]) * P.vx()[i] + double(P.vy()[i]) * P.vy()[i] +
                                            double(P.vz()[i]) * P.vz()[i]));
    const double h = 0.02, viscous = 0.125 * (h / 2) * (h / 2) / 0.01, courant = 0.15 * h / (1.0 + fastest);
    EXPECT_NEAR(sim.timestep(), kind == "laplacian" ? viscous : courant, 1e-12) << kind;
  }
}
