// Stability (issue 10). Particles that start on top of one another would move as one for ever
// (no kernel gradient between them): a run moves them apart by a rule of positions and ids,
// with one warning giving the count, the same bits at any thread count. And a step beyond
// the largest stable one stops the run with one message naming the step, the particle, the
// quantity and the step that would do, rather than running on into garbage (the bisection
// that finds the largest stable steps is share/validation/stable_step.py; docs/physics.md,
// "The largest stable step").
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <omp.h>
#include <regex>
#include <sstream>
#include <spdlog/sinks/ostream_sink.h>
#include <spdlog/spdlog.h>

#include "engine/core/simulation.hpp"
#include "engine/registry/style_registry.hpp"
#include "engine/sph/lattice.hpp"
#include "engine/sph/separate_coincident.hpp"
#include "test_util.hpp"

using namespace pbf;
using pbf::test::run_engine;
using pbf::test::LogCapture;
using pbf::test::scenario;

namespace {

constexpr double kS = 0.01, kH = 2 * kS;
// The sites that get duplicates: a pair inside, a pair against the wall y = 0.1 (its first
// direction would leave the domain), a triple.
constexpr double kPairA[3] = {0.055, 0.055, 0.055}, kPairB[3] = {0.055, 0.095, 0.035},
                 kTriple[3] = {0.025, 0.045, 0.065};

// A block of water at rest, 10 x 10 x 10 particles at 1 cm in a box twice as tall (ids
// 0..999), then the duplicates (ids 1000..1003: one on each pair's site, two on the triple's)
// and the pipeline of `solver` at a step well within its stable one.
void duplicated_block(Simulation& sim, const std::string& solver) {
  sim.set_domain(Domain{{0, 0, 0}, {0.1, 0.1, 0.2}});
  sim.set_kernel_radius(kH);
  sim.set_timestep(solver == "pbf" ? 0.004 : 1e-4);
  const double lo[3] = {0, 0, 0}, hi[3] = {0.1, 0.1, 0.1}, rest[3] = {0, 0, 0};
  add_lattice(sim, lo, hi, kS, rest);
  auto& P = sim.particles();
  const real m = P.mass()[0], v[3] = {0, 0, 0};
  for (const double* site : {kPairA, kPairB, kTriple, kTriple}) {
    const real x[3] = {real(site[0]), real(site[1]), real(site[2])};
    P.add(x, v, m);
  }
  const auto& styles = StyleRegistry::builtin();
  sim.add_fix(styles.make_fix("gravity", "gravity", {}));
  if (solver == "pbf") {
    sim.add_fix(styles.make_fix("pbf", "pbf", {}));
  } else {
    sim.add_fix(styles.make_fix("integrator", "leapfrog", {}));
    sim.add_fix(styles.make_fix("wcsph", "wcsph", {}));
    sim.add_fix(styles.make_fix("viscosity", "sph_viscosity", {}));
  }
  sim.add_fix(styles.make_fix("walls", "box", {}));
}

// The distance between the particles with ids a and b.
double distance(const Simulation& sim, std::int64_t a, std::int64_t b) {
  const auto& P = sim.particles();
  const auto at = P.index_of_id();
  const std::size_t i = at[a], j = at[b];
  const double dx = P.x()[i] - P.x()[j], dy = P.y()[i] - P.y()[j], dz = P.z()[i] - P.z()[j];
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

// The id of the lattice particle on a site (the lattice fills x fastest, then y, then z).
std::int64_t site_id(const double site[3]) {
  auto layer = [](double c) { return static_cast<std::int64_t>(std::lround((c - kS / 2) / kS)); };
  return layer(site[0]) + 10 * layer(site[1]) + 100 * layer(site[2]);
}

}  // namespace

// The rule itself (a run of 0 steps only prepares): the lowest id of each group stays, the
// k-th higher one moves kApart h along the k-th icosahedron direction, (0, 1, phi) and then its
// opposite, with a component turned back where it would leave the domain; and it does not
// depend on the particles' order in memory.
TEST(Stability, CoincidentParticlesMoveByARuleOfPositionsAndIds) {
  Simulation sim, reversed;
  duplicated_block(sim, "pbf");
  duplicated_block(reversed, "pbf");
  std::vector<std::uint32_t> order(reversed.particles().size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<std::uint32_t>(order.size() - 1 - i);
  reversed.particles().permute(order);
  {
    LogCapture log;
    sim.run(0);
    reversed.run(0);
    EXPECT_EQ(log.count("4 particles started on top of another"), 2) << log.text();
  }
  const double phi = (1 + std::sqrt(5.0)) / 2, norm = std::sqrt(1 + phi * phi), step = kApart * kH;
  const auto& P = sim.particles();
  const auto at = P.index_of_id();
  // 1e-6 m: positions near 0.1 m are exact to 6e-9 m in single precision; a wrong direction is 0.01 m off.
  auto expect_at = [&](std::int64_t id, double x, double y, double z) {
    const std::size_t i = at[id];
    EXPECT_NEAR(P.x()[i], x, 1e-6) << "id " << id;
    EXPECT_NEAR(P.y()[i], y, 1e-6) << "id " << id;
    EXPECT_NEAR(P.z()[i], z, 1e-6) << "id " << id;
  };
  expect_at(site_id(kPairA), kPairA[0], kPairA[1], kPairA[2]);
  expect_at(1000, kPairA[0], kPairA[1] + step / norm, kPairA[2] + step * phi / norm);
  expect_at(1001, kPairB[0], kPairB[1] - step / norm, kPairB[2] + step * phi / norm);  // y turned back
  expect_at(site_id(kTriple), kTriple[0], kTriple[1], kTriple[2]);
  expect_at(1002, kTriple[0], kTriple[1] + step / norm, kTriple[2] + step * phi / norm);
  expect_at(1003, kTriple[0], kTriple[1] - step / norm, kTriple[2] - step * phi / norm);
  const auto& Q = reversed.particles();
  const auto at_q = Q.index_of_id();
  for (std::size_t k = 0; k < P.size(); ++k) {
    EXPECT_EQ(P.x()[at[k]], Q.x()[at_q[k]]) << "id " << k;
    EXPECT_EQ(P.y()[at[k]], Q.y()[at_q[k]]) << "id " << k;
    EXPECT_EQ(P.z()[at[k]], Q.z()[at_q[k]]) << "id " << k;
  }
}

// Before, the duplicates stayed on their sites for ever (0 m apart after 200 PBF steps or
// 2000 WCSPH steps), and a triple stopped WCSPH at its first step at 1.8 rho0. Now both
// solvers run, keep every particle, and the duplicates stay apart; the warning comes once,
// with the count, and not again in a second run.
TEST(Stability, BothSolversRunADuplicatedLatticeAndSeparateIt) {
  for (const std::string solver : {"pbf", "wcsph"}) {
    Simulation sim;
    duplicated_block(sim, solver);
    LogCapture log;
    const int steps = solver == "pbf" ? 50 : 500;  // 0.2 s, 0.05 s
    sim.run(steps);
    sim.run(steps);
    EXPECT_EQ(log.count("started on top of another"), 1) << solver << ": " << log.text();
    EXPECT_EQ(log.count("4 particles started on top of another (closer than 0.0002 m, 0.01 h): moved apart by "
                        "0.01 m (0.5 h)"),
              1)
        << solver << ": " << log.text();
    EXPECT_EQ(sim.particles().size(), 1004u) << solver;
    // Apart by more than h/4: in a fluid at rest density neighbours sit a spacing, h/2, apart;
    // duplicates left together are 0 apart.
    for (const double* site : {kPairA, kPairB, kTriple}) {
      const std::int64_t first = site_id(site);
      const std::int64_t duplicate = site == kPairA ? 1000 : site == kPairB ? 1001 : 1002;
      EXPECT_GT(distance(sim, first, duplicate), 0.25 * kH) << solver << ", site of id " << first;
    }
    EXPECT_GT(distance(sim, site_id(kTriple), 1003), 0.25 * kH) << solver;
    EXPECT_GT(distance(sim, 1002, 1003), 0.25 * kH) << solver;
  }
}

// The separation and the run after it are the same bits at 1 and 2 threads.
TEST(Stability, DuplicatedLatticeIsTheSameBitsAtOneAndTwoThreads) {
  for (const std::string solver : {"pbf", "wcsph"}) {
    std::vector<real> state[2];
    for (int t = 0; t < 2; ++t) {
      omp_set_num_threads(t + 1);
      Simulation sim;
      duplicated_block(sim, solver);
      sim.run(solver == "pbf" ? 10 : 30);
      const auto& P = sim.particles();
      for (const real* a : {P.x(), P.y(), P.z(), P.vx(), P.vy(), P.vz()}) state[t].insert(state[t].end(), a, a + P.size());
    }
    omp_set_num_threads(1);
    ASSERT_EQ(state[0].size(), state[1].size());
    EXPECT_EQ(std::memcmp(state[0].data(), state[1].data(), state[0].size() * sizeof(real)), 0) << solver;
  }
}

// Just beyond its largest stable step (10.9 ms for the 1000-particle dam break) PBF stops with
// one message: the step, the particle, how far it moved, and the step that would do; just
// below, the run goes to its end. WCSPH stops on its density limit, naming the CFL bound.
TEST(Stability, StepsBeyondTheStableOneStopLoudly) {
  const std::string dambreak = "run " + scenario("dambreak.lua") + " --threads 1 -v particles=1000 -v t_end=0.5 -v out=";
  const auto below = run_engine(dambreak + " -v dt=0.009");
  EXPECT_EQ(below.code, 0) << below.output;

  const auto beyond = run_engine(dambreak + " -v dt=0.016");
  EXPECT_EQ(beyond.code, 1) << beyond.output;
  const std::regex pbf_stop(
      "dambreak\\.lua:[0-9]+: step [0-9]+: fix 'pbf' \\(pbf\\): particle [0-9]+ moved [0-9.]+ m in one step, [0-9.]+ "
      "h \\(more than 2 h: past neighbours the solver never saw\\), at [0-9.]+ m/s: the time step 0\\.016 s is too "
      "large \\(or a setting unstable, such as relaxation above 0\\.77\\); the largest stable at this speed is about "
      "1\\.5 h / [0-9.]+ m/s = [0-9.e-]+ s");
  EXPECT_TRUE(std::regex_search(beyond.output, pbf_stop)) << beyond.output;
  EXPECT_EQ(beyond.output.find("too large"), beyond.output.rfind("too large")) << beyond.output;  // one message

  // WCSPH: h / c0 = 0.02 m / 19.81 m/s = 1.01 ms, the largest stable step measured (above).
  const std::string wcsph = dambreak + " -v solver=wcsph -v fixed_dt=true";
  const auto wcsph_below = run_engine(wcsph + " -v dt=0.0009");
  EXPECT_EQ(wcsph_below.code, 0) << wcsph_below.output;
  const auto wcsph_beyond = run_engine(wcsph + " -v dt=0.00103");
  EXPECT_EQ(wcsph_beyond.code, 1) << wcsph_beyond.output;
  const std::regex wcsph_stop(
      "step 1: fix 'wcsph' \\(wcsph\\): the time step 0\\.00103 s is beyond WCSPH's stable limit h / c0 = "
      "0\\.00101 s for the sound speed 19\\.81 m/s");
  EXPECT_TRUE(std::regex_search(wcsph_beyond.output, wcsph_stop)) << wcsph_beyond.output;
}
