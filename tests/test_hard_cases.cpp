// Hard cases (issue 10): violent starts that break fluid codes, each for both solvers. Every
// run must keep every particle in the domain, stay finite and bound its density error. A start
// at rest density without vorticity confinement must never gain energy: PBF's constraint
// stores none, so its kinetic plus potential energy; WCSPH's equation of state stores elastic
// energy, counted here (tests/test_energy.cpp has the dam break). A compressed start must
// throw no particle faster than a bound derived from what it stores.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include <fmt/format.h>

#include "engine/core/error.hpp"
#include "engine/core/simulation.hpp"
#include "engine/registry/style_registry.hpp"
#include "engine/sph/lattice.hpp"
#include "engine/sph/mass.hpp"

using namespace pbf;

namespace {

const StyleRegistry& styles() { return StyleRegistry::builtin(); }

std::unique_ptr<Fix> fix(const std::string& id, const std::string& style, const GivenParams& p = {}) {
  return styles().make_fix(id, style, p);
}

double value(Simulation& sim, const std::string& id, std::size_t k = 0) {
  std::vector<double> v;
  sim.find_compute(id)->evaluate(sim, v);
  return v.at(k);
}

const double g = 9.81, gamma_tait = 7;  // wcsph's defaults: gravity, the Tait exponent of water
const std::int64_t kIterations = 4;     // pbf's default

// The solver as share/lua/solvers.lua assembles it: pbf with its defaults (`iterations` for the
// convergence check below), or WCSPH (leapfrog, wcsph with sound speed c0, artificial
// viscosity, cfl choosing each step under the script's).
// DFSPH as solvers.lua has it too: dfsph at its tolerances, a Laplacian viscosity of 1e-3 m^2/s
// and cfl with courant 0.4 (0.2 for the convergence check, `iterations` twice the default: its
// compression is what a step's drift makes before the next solve removes it, so it falls with
// the step, not with the tolerance).
void add_solver(Simulation& sim, const std::string& solver, double c0, const GivenParams& wcsph = {},
                const GivenParams& cfl = {}, std::int64_t iterations = kIterations) {
  if (solver == "pbf") {
    sim.add_fix(fix("pbf", "pbf", {{"iterations", iterations}}));
    return;
  }
  if (solver == "dfsph") {
    sim.add_fix(fix("dfsph", "dfsph", {}));
    sim.add_fix(fix("viscosity", "sph_viscosity", {{"kind", std::string("laplacian")}, {"nu", 1e-3}}));
    sim.add_fix(fix("cfl", "cfl", {{"courant", iterations == kIterations ? 0.4 : 0.2}}));
    return;
  }
  GivenParams p = wcsph;
  p.push_back({"sound_speed", c0});
  sim.add_fix(fix("integrator", "leapfrog"));
  sim.add_fix(fix("wcsph", "wcsph", p));
  sim.add_fix(fix("viscosity", "sph_viscosity"));
  sim.add_fix(fix("cfl", "cfl", cfl));
}

// The elastic energy WCSPH's Tait equation stores (pressures below rho0 clamped to 0):
// sum_i m_i e(rho_i), e(rho) = integral from rho0 to rho of p / rho'^2 drho'
//   = c0^2 / gamma ((x^(gamma-1) - 1) / (gamma - 1) + 1/x - 1),  x = rho/rho0 > 1 (else 0).
// The pressure force between particles is minus its gradient, so WCSPH keeps kinetic plus
// potential plus this, less what the viscosity takes (near walls only nearly: a wall mirrors
// the particle's pressure). PBF stores none.
double elastic_energy(Simulation& sim, const std::string& solver, double c0) {
  if (solver != "wcsph") return 0;  // PBF and DFSPH store none
  const auto& P = sim.particles();
  const real* rho = sim.solver_density();
  double sum = 0;
  for (std::size_t i = 0; i < P.size(); ++i) {
    const double x = rho[i] / sim.rest_density();
    if (x > 1) sum += P.mass()[i] * ((std::pow(x, gamma_tait - 1) - 1) / (gamma_tait - 1) + 1 / x - 1);
  }
  return sum * c0 * c0 / gamma_tait;
}

// DFSPH's step ends between its kick and its drift: the velocity holds gravity's last kick,
// the positions not yet the drift it makes (symplectic Euler). That integrator conserves
// KE + PE + (dt/2) g sum_i m_i v_z,i (exactly, in a free fall: each step's kick adds
// g^2 dt^2 / 2 to KE + PE, and takes it from the last term), so that is its energy here.
double staggering(Simulation& sim, const std::string& solver) {
  if (solver != "dfsph") return 0;
  const auto& P = sim.particles();
  double momentum = 0;
  for (std::size_t i = 0; i < P.size(); ++i) momentum += P.mass()[i] * P.vz()[i];
  return sim.timestep() / 2 * g * momentum;
}

double energy(Simulation& sim, const std::string& solver, double c0) {
  return value(sim, "ke") + value(sim, "pe") + elastic_energy(sim, solver, c0) + staggering(sim, solver);
}

// Every particle still there, finite and inside the domain.
::testing::AssertionResult intact(const Simulation& sim, std::size_t n) {
  const auto& P = sim.particles();
  if (P.size() != n) return ::testing::AssertionFailure() << P.size() << " particles of " << n;
  for (std::size_t i = 0; i < n; ++i)
    if (!sim.domain().contains(P.x()[i], P.y()[i], P.z()[i]) || !std::isfinite(P.vx()[i] + P.vy()[i] + P.vz()[i]))
      return ::testing::AssertionFailure() << "particle " << P.ids()[i] << " at (" << P.x()[i] << ", " << P.y()[i]
                                           << ", " << P.z()[i] << ")";
  return ::testing::AssertionSuccess();
}

// Watches a run after every step, as an output does (the step finished): every particle must be
// there, finite and inside the domain (else it stops the run), and it keeps the extremes.
class Watch : public Fix {
 public:
  Watch(const Simulation& sim, std::string solver, double c0)
      : Fix("watch", "watch"), solver_(std::move(solver)), c0_(c0), n_(sim.particles().size()) {}
  std::vector<Stage> stages() const override { return {Stage::end_of_step}; }
  Role role() const override { return Role::output; }
  void init(Simulation& sim) override {  // the start of the first run is the start
    if (!started_) start_ = energy(sim, solver_, c0_), started_ = true;
  }
  void end_of_step(Simulation& sim) override {
    const auto kept = intact(sim, n_);
    if (!kept) throw Error(fmt::format("{}, t = {}", kept.message(), sim.time()));
    rise = std::max(rise, energy(sim, solver_, c0_) / start_ - 1);
    densest = std::max(densest, value(sim, "err", 1));
    fastest = std::max(fastest, value(sim, "speed"));
  }

  double rise = -1;     // the most the energy rose above its start, relative to the start
  double densest = -1;  // the largest rho/rho0 - 1
  double fastest = 0;   // the fastest particle (m/s)

 private:
  std::string solver_;
  double c0_, start_ = 0;
  bool started_ = false;
  std::size_t n_;
};

// Runs to t_end under a Watch, which it returns.
const Watch& run_watching(Simulation& sim, const std::string& solver, double c0, double t_end) {
  sim.add_compute(styles().make_compute("ke", "kinetic_energy", {}));
  sim.add_compute(styles().make_compute("pe", "potential_energy", {}));
  sim.add_compute(styles().make_compute("err", "density_error", {}));
  sim.add_compute(styles().make_compute("speed", "speed", {}));
  auto watch = std::make_unique<Watch>(sim, solver, c0);
  const Watch& seen = *watch;
  sim.add_fix(std::move(watch));
  sim.run_until(t_end);
  return seen;
}

// What a Watch saw, kept after its simulation is gone.
struct Seen {
  double rise, densest, fastest;
};
Seen seen_of(const Watch& w) { return {w.rise, w.densest, w.fastest}; }

// PBF's density error is no physical compression (its fluid is incompressible) but what its
// Jacobi iterations leave, so its bound is one of convergence: twice the iterations leave less.
// Each iteration multiplies a density mode by 1 - omega a(k) / (1 + epsilon), at most 1 in size
// at omega = 0.7 < 0.77 (engine/fixes/pbf.cpp, tests/test_pbf_convergence.cpp), and the long
// modes shrink by nearly 1 (a(k) ~ k^2), so the factor has no bound below 1: the check is
// "less", not a ratio. Measured 2026-11-28 (4 -> 8 iterations): cube 4.7% -> 2.0%, column 3.9%
// -> 0.9%, full box 21% -> 13%. It fails where more iterations do not help: one iteration
// whatever the count (seen: 34%, 20%, 140% at both counts; the old bound, 100%, let the first
// two pass), corrections that do not shrink the error. (The full box keeps 11% at 100
// iterations: pbf's neighbour lists, built at the predicted positions, miss the pairs the
// prediction carries 2 U dt = 0.46 h apart across the mid-planes and the corrections bring back.)
::testing::AssertionResult converges(const Seen& default_count, const Seen& twice) {
  if (twice.densest < default_count.densest) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "largest compression " << default_count.densest << " at " << kIterations
                                       << " iterations, " << twice.densest << " at " << 2 * kIterations;
}

// The tolerance on "energy never above its start" (a start at rest density): PBF within 1e-9,
// far above the sums' rounding; WCSPH, its elastic energy counted, within 1e-5: the leapfrog
// keeps energy only up to a bounded error of second order in the step (measured at most 7e-7
// here, 2026-11-26).
double energy_tolerance(const std::string& solver) { return solver == "pbf" ? 1e-9 : 1e-5; }

std::string solver_name(const ::testing::TestParamInfo<std::string>& info) { return info.param; }

}  // namespace

// A cube 5 cm on a side hits a pool 5 cm deep at 9.9 m/s, the speed of a fall from 5 m
// (sqrt(2 g 5 m)); it starts just above the surface with that speed, which is the same impact
// without 1 s of free fall. PBF's step keeps the impact speed to 0.4 h a step; WCSPH gets a
// sound speed ten times the impact speed (99 m/s, Mach 0.1) and cfl steps under that one.
// Through the splash (0.05 s): every particle kept, energy never above its start, and the
// largest compression: for WCSPH below the Mach number v/c0 = 0.1 (an impact at v compresses a
// fluid of sound speed c0 by v/c0, the water hammer); for PBF less with 8 iterations than with
// 4 (`converges` above), and below 100% whatever the count (rho < 2 rho0: a fluid, not particles
// on top of one another). Measured 2026-11-26: PBF 4.7%, WCSPH 5.3%.
class CubeDrop : public ::testing::TestWithParam<std::string> {};

TEST_P(CubeDrop, FromFiveMetresIntoAShallowPool) {
  const std::string solver = GetParam();
  const double s = 0.01, impact = std::sqrt(2 * g * 5.0), c0 = 10 * impact;
  auto run = [&](std::int64_t iterations) {
    Simulation sim;
    sim.set_domain(Domain{{0, 0, 0}, {0.3, 0.3, 0.4}});
    sim.set_kernel_radius(2 * s);
    sim.set_timestep(0.4 * 2 * s / impact);
    const double pool_lo[3] = {0, 0, 0}, pool_hi[3] = {0.3, 0.3, 0.05}, rest[3] = {0, 0, 0};
    add_lattice(sim, pool_lo, pool_hi, s, rest);
    const double cube_lo[3] = {0.125, 0.125, 0.07}, cube_hi[3] = {0.175, 0.175, 0.12}, down[3] = {0, 0, -impact};
    add_lattice(sim, cube_lo, cube_hi, s, down);
    sim.add_fix(fix("gravity", "gravity"));
    add_solver(sim, solver, c0, {}, {}, iterations);
    sim.add_fix(fix("walls", "box"));
    return seen_of(run_watching(sim, solver, c0, 0.05));
  };
  const Seen seen = run(kIterations);
  EXPECT_LE(seen.rise, energy_tolerance(solver));
  EXPECT_LT(seen.densest, solver != "wcsph" ? 1.0 : impact / c0);
  if (solver != "wcsph") EXPECT_TRUE(converges(seen, run(2 * kIterations)));
  EXPECT_GT(seen.densest, 0.0);  // it did hit the pool
}

INSTANTIATE_TEST_SUITE_P(HardCases, CubeDrop, ::testing::Values("pbf", "wcsph", "dfsph"), solver_name);

// A column 4 cm square and 32 cm high (aspect ratio 8), at rest and at rest density in the
// middle of a 0.4 m square floor, collapses and spreads. PBF at 0.4 h / sqrt(2 g H) a step;
// WCSPH with the default rule's sound speed, c0 = 10 sqrt(2 g H). To t = 0.4 s (the centre of
// mass falls its 0.16 m freely in 0.18 s): every particle kept, energy never above its start,
// the density error bounded as for the cube (WCSPH: by the Mach number of the free fall, 0.1),
// and the column collapsed: its centre of mass below a quarter of its start height (a
// collapsed column is a layer a few particles thick: spread over the floor at rest it would be
// under a spacing deep, its centre of mass at 3% of the start height; one still standing keeps
// 50%). Measured 2026-11-26: compression PBF 3.9%, WCSPH 4.4%; centre of mass at 11% (PBF) and
// 10% (WCSPH) of its start height.
class ThinColumn : public ::testing::TestWithParam<std::string> {};

TEST_P(ThinColumn, CollapsesWithoutGainingEnergy) {
  const std::string solver = GetParam();
  const double s = 0.01, width = 0.04, height = 8 * width, fall = std::sqrt(2 * g * height), c0 = 10 * fall;
  double centre = 0;  // of the default run, at the end
  auto run = [&](std::int64_t iterations) {
    Simulation sim;
    sim.set_domain(Domain{{0, 0, 0}, {0.4, 0.4, 0.4}});
    sim.set_kernel_radius(2 * s);
    sim.set_timestep(0.4 * 2 * s / fall);
    const double lo[3] = {0.18, 0.18, 0}, hi[3] = {0.22, 0.22, height}, rest[3] = {0, 0, 0};
    add_lattice(sim, lo, hi, s, rest);
    sim.add_fix(fix("gravity", "gravity"));
    add_solver(sim, solver, c0, {}, {}, iterations);
    sim.add_fix(fix("walls", "box"));
    const Seen seen = seen_of(run_watching(sim, solver, c0, 0.4));
    const auto& P = sim.particles();
    if (iterations == kIterations)
      centre = value(sim, "pe") / (std::accumulate(P.mass(), P.mass() + P.size(), 0.0) * g);
    return seen;
  };
  const Seen seen = run(kIterations);
  EXPECT_LE(seen.rise, energy_tolerance(solver));
  EXPECT_LT(seen.densest, solver != "wcsph" ? 1.0 : fall / c0);
  if (solver != "wcsph") EXPECT_TRUE(converges(seen, run(2 * kIterations)));
  EXPECT_LT(centre, height / 2 / 4);  // the centre of mass's height
}

INSTANTIATE_TEST_SUITE_P(HardCases, ThinColumn, ::testing::Values("pbf", "wcsph", "dfsph"), solver_name);

// A block 8 cm on a side at twice the rest density (particles of the rest-density mass of
// spacing s = 1 cm packed at s / 2^(1/3); their SPH sum is 1.96 rho0), at rest in the middle
// of a closed 0.3 m box, expands into it. No particle is faster than v_expand, in quadrature
// with a fall from the top of the box (sqrt(v_expand^2 + 2 g 0.3 m), by energy):
// - WCSPH: v_expand = 7/3 c0. The fastest fluid of an expansion into vacuum is the head of a
//   planar rarefaction, whose Riemann invariant u + integral c drho/rho gives u = integral
//   from rho0 to 2 rho0 of c drho/rho, with Tait's c = c0 (rho/rho0)^((gamma-1)/2):
//   2 c0 / (gamma - 1) (2^3 - 1) = 7/3 c0 (below rho0 the clamped pressure does no work). An
//   expansion in three dimensions spreads the same energy over more directions. The sound
//   speed at 2 rho0 is 8 c0, so cfl is given it (with c0 alone the first step is 8 times too
//   long: it kicks the block with more than all the energy it stores, docs/physics.md "Hard
//   cases"), and the density guard (max_density_error) lets the start pass.
// - PBF stores no energy: its step turns the displacement that removes a compression into
//   velocity, x / dt. Removing it all grows the block by 2^(1/3) about its centre, which moves
//   a corner by (2^(1/3) - 1) sqrt(3) a / 2, a the side; no particle needs to move further in
//   one step: v_expand = (2^(1/3) - 1) sqrt(3) a / (2 dt).
// Measured 2026-11-26: WCSPH 25.5 m/s (bound 31.0), PBF 12.1 m/s at dt = 1 ms (bound 18.0).
// Also: every particle kept, and none ever more compressed than at the start.
class CompressedBlock : public ::testing::TestWithParam<std::string> {};

TEST_P(CompressedBlock, ExpandsNoFasterThanItsBound) {
  const std::string solver = GetParam();
  Simulation sim;
  const double s = 0.01, side = 10 * s / std::cbrt(2.0), box = 0.3, dt = 0.001;
  const double c0 = 10 * std::sqrt(2 * g * (side + s));  // wcsph's default rule
  sim.set_domain(Domain{{0, 0, 0}, {box, box, box}});
  sim.set_kernel_radius(2 * s);
  sim.set_timestep(dt);
  const double lo[3] = {(box - side) / 2, (box - side) / 2, (box - side) / 2},
               hi[3] = {(box + side) / 2, (box + side) / 2, (box + side) / 2}, rest[3] = {0, 0, 0};
  add_lattice(sim, lo, hi, s / std::cbrt(2.0), rest);
  auto& P = sim.particles();
  std::fill(P.mass(), P.mass() + P.size(), real(lattice_mass(s, sim.kernels(), sim.rest_density())));
  sim.add_fix(fix("gravity", "gravity"));
  add_solver(sim, solver, c0, {{"max_density_error", 1.0}}, {{"sound_speed", 8 * c0}});
  sim.add_fix(fix("walls", "box"));
  sim.add_compute(styles().make_compute("start", "density_error", {}));
  const double start = value(sim, "start", 1);
  ASSERT_GT(start, 0.9);
  const Watch& seen = run_watching(sim, solver, c0, 0.05);
  const double expand = solver != "wcsph" ? (std::cbrt(2.0) - 1) * std::sqrt(3.0) * side / 2 / dt : 7.0 / 3 * c0;
  EXPECT_LT(seen.fastest, std::sqrt(expand * expand + 2 * g * box));
  EXPECT_LE(seen.densest, start);
}

INSTANTIATE_TEST_SUITE_P(HardCases, CompressedBlock, ::testing::Values("pbf", "wcsph", "dfsph"), solver_name);

// A closed box 8 cm on a side filled with fluid at rest density: a lattice of spacing s = 1 cm
// whose outer particles lie s/2 from the faces, on every face, edge and corner (exactly where
// the box fix's contact distance holds them). Every particle moves at U = 1 m/s along each axis
// towards the nearer face, so the whole fluid presses into every face (U), edge (sqrt(2) U) and
// corner (sqrt(3) U) at once; PBF's step keeps sqrt(3) U to 0.4 h. Walls: the box fix, or a
// solid container the size of the domain. To t = 0.1 s: every particle kept inside the domain,
// energy never above its start, and the density error for PBF and DFSPH as for the cube (less
// with 8 iterations or half the Courant number, below 100%) and, for WCSPH, below 3 U / c0 + 0.05: linear acoustics superposes in
// a corner the water hammers of three walls, U / c0 each, and a particle pressed into a corner
// adds what SPH's walls get wrong there: their density is exact to about 2% of rho0 at edges
// and corners (docs/physics.md, "box"), and a wall counts as fluid at rest density, so the
// fluid beside it takes the whole compression. Measured 2026-11-26: PBF 21% (both walls), WCSPH
// 24.9% (box) and 25.1% (solid) against 3 U / c0 = 22.6%; 2026-11-29: DFSPH 93% (box), in the
// second step, before its solve has turned the fluid (its first drift carries the start's
// velocity unsolved).
class FullBox : public ::testing::TestWithParam<std::string> {};

TEST_P(FullBox, HoldsFluidPressedIntoEveryCornerAndFace) {
  const std::string param = GetParam(), solver = param.substr(0, param.find('_'));
  const double s = 0.01, L = 8 * s, c0 = 10 * std::sqrt(2 * g * (L + s)), U = 1.0;
  auto run = [&](std::int64_t iterations) {
    Simulation sim;
    sim.set_domain(Domain{{0, 0, 0}, {L, L, L}});
    sim.set_kernel_radius(2 * s);
    sim.set_timestep(0.4 * 2 * s / (std::sqrt(3.0) * U));
    const double lo[3] = {0, 0, 0}, hi[3] = {L, L, L}, none[3] = {0, 0, 0};
    add_lattice(sim, lo, hi, s, none);
    auto& P = sim.particles();
    for (std::size_t i = 0; i < P.size(); ++i) {
      P.vx()[i] = real(P.x()[i] < L / 2 ? -U : U);
      P.vy()[i] = real(P.y()[i] < L / 2 ? -U : U);
      P.vz()[i] = real(P.z()[i] < L / 2 ? -U : U);
    }
    sim.add_fix(fix("gravity", "gravity"));
    add_solver(sim, solver, c0, {}, {}, iterations);
    if (param.find("solid") != std::string::npos)
      sim.add_fix(fix("tank", "solid", {{"shape", std::string("box")}, {"fluid", std::string("inside")},
                                        {"lo", Vec3{0, 0, 0}}, {"hi", Vec3{L, L, L}}}));
    else
      sim.add_fix(fix("walls", "box"));
    return seen_of(run_watching(sim, solver, c0, 0.1));
  };
  const Seen seen = run(kIterations);
  EXPECT_LE(seen.rise, energy_tolerance(solver));
  EXPECT_LT(seen.densest, solver != "wcsph" ? 1.0 : 3 * U / c0 + 0.05);
  if (solver != "wcsph") EXPECT_TRUE(converges(seen, run(2 * kIterations)));
}

INSTANTIATE_TEST_SUITE_P(HardCases, FullBox,
                         // (DFSPH in the solid container: 796% at its corners. The solid holds particles half
                         // a spacing off, where its wall's pressure has not yet begun to push: the inner layers
                         // press the outer ones onto a projection the solves cannot see, as in the box before
                         // its quarter spacing (physics.md, "DFSPH at walls"). At a quarter spacing: 117%, and
                         // the mesh container's resting column then jostles at 77 mm/s at an edge; open.)
                         ::testing::Values("pbf_box", "pbf_solid", "wcsph_box", "wcsph_solid", "dfsph_box"),
                         solver_name);
