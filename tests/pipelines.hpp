#pragma once
// Scenes with every pipeline that keeps state from step to step, for the tests that run
// each of them twice and compare the bits: a restart in the middle (test_restart_pipelines.cpp)
// and the ghost-refresh check (test_ghost_refresh.cpp). A block of 10 x 10 x 8 particles
// moving along x in a box twice as long; the pipelines by name.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "engine/core/simulation.hpp"
#include "engine/geometry/motion.hpp"
#include "engine/geometry/space_time_function.hpp"
#include "engine/registry/style_registry.hpp"
#include "engine/sph/lattice.hpp"

namespace pbf::test {

struct StyleSpec {
  std::string id, style;
  GivenParams params;
};

// A scene and its pipeline: fixes and computes, in the order they are added.
struct Pipeline {
  double dt;
  std::vector<StyleSpec> fixes, computes;
};

inline const StyleSpec kGravity{"gravity", "gravity", {}}, kWalls{"walls", "box", {}};

// The WCSPH solver with the given density and Monaghan's artificial viscosity.
inline std::vector<StyleSpec> wcsph(const std::string& density) {
  return {kGravity,
          {"integrator", "leapfrog", {}},
          {"wcsph", "wcsph", {{"density", density}}},
          {"viscosity", "sph_viscosity", {{"kind", std::string("artificial")}}}};
}

// An inflow that a script would give as a Lua function: a profile across x that grows in time,
// with a part along x, over an opening centred at x = 0.15 m, 4 cm across.
struct GrowingProfile : SpaceTimeFunction {
  Vec3 at(double t, const Vec3& x) const override {
    const double across = (x[0] - 0.15) / 0.02;
    return {0.1 * across, 0, -(0.3 + 20 * t) * (1 - across * across)};
  }
  bool constant() const override { return false; }
  std::string description() const override { return "a growing profile"; }
};

// A paddle at the block's back (x = 0), pushing it on a spline: it reaches `x1` at `t1` and
// `x2`, turned, at `t2`.
inline StyleSpec paddle(double t1, double x1, double t2, double x2) {
  const std::vector<Keyframes::Key> keys = {
      {0, {}}, {t1, Pose{{x1, 0, 0}, {0, 0, 0}}}, {t2, Pose{{x2, 0, 0}, {0, 2, 0}}}};
  const MotionPtr motion = std::make_shared<Keyframes>(keys, Keyframes::Interpolation::spline, "paddle");
  return {"paddle",
          "solid",
          {{"shape", std::string("box")}, {"lo", Vec3{-0.05, 0, 0}}, {"hi", Vec3{0.0005, 0.1, 0.2}}, {"motion", motion}}};
}

// A crate of pine (600 kg/m^3) in the block's way, spinning as it is released.
inline StyleSpec crate(const GivenParams& more) {
  GivenParams p = {{"shape", std::string("box")},
                   {"lo", Vec3{0.12, 0.03, 0.01}},
                   {"hi", Vec3{0.16, 0.07, 0.07}},
                   {"density", 600.0},
                   {"angular_velocity", Vec3{0.5, 1, 0}}};
  p.insert(p.end(), more.begin(), more.end());
  return {"crate", "solid", p};
}

// The pipelines, by name; outputs go to `out`. Time steps: 2 ms for PBF; 0.2 ms for WCSPH,
// under the CFL bound 0.15 h / c0 = 0.24 ms with c0 = 10 sqrt(2 g 0.08 m), or chosen by the
// `cfl` fix.
inline Pipeline pipeline(const std::string& name, const std::filesystem::path& out) {
  if (name == "PbfVorticityXsph")
    return {0.002, {kGravity, {"pbf", "pbf", {}}, {"vorticity", "vorticity", {}}, {"xsph", "xsph", {}}, kWalls}, {}};
  if (name == "WcsphSummationLeapfrogArtificialViscosity") {
    auto fixes = wcsph("summation");
    fixes.push_back(kWalls);
    return {0.0002, fixes, {}};
  }
  if (name == "WcsphContinuityCfl") {
    auto fixes = wcsph("continuity");
    fixes[2].params.push_back({"diffusion", 0.1});
    fixes.push_back({"cfl", "cfl", {}});
    fixes.push_back(kWalls);
    return {0.001, fixes, {}};  // the largest step: the CFL bound chooses each
  }
  if (name == "PbfSolid")  // a sphere in the way of the block, which moves towards it
    return {0.002,
            {kGravity,
             {"pbf", "pbf", {}},
             kWalls,
             {"ball",
              "solid",
              {{"shape", std::string("sphere")}, {"center", Vec3{0.14, 0.05, 0.03}}, {"radius", 0.03}}}},
            {}};
  if (name == "WcsphMovingSolid") {  // a paddle at the block's back, pushing it on a spline
    auto fixes = wcsph("summation");
    fixes.push_back(kWalls);
    fixes.push_back(paddle(0.003, 0.002, 0.006, 0.003));
    return {0.0002, fixes, {}};
  }
  if (name == "SampleProbesGauge") {  // every 2 steps a row; a restart every 10 steps, 2 kept
    const Points points = {{0.05, 0.05, 0.01}, {0.09, 0.05, 0.05}};
    return {0.002,
            {kGravity,
             {"pbf", "pbf", {}},
             kWalls,
             {"sample",
              "sample",
              {{"computes", Names{"p", "v", "rho", "h"}}, {"interval", 0.004}, {"file", (out / "s.csv").string()}}},
             {"restarts", "restart", {{"path", (out / "r.*.restart").string()}, {"every", std::int64_t{10}}}}},
            {{"p", "probe", {{"points", points}}},
             {"v", "probe", {{"points", points}, {"field", std::string("velocity")}}},
             {"rho", "probe", {{"points", points}, {"field", std::string("density")}}},
             {"h", "gauge", {{"points", points}}}}};
  }
  // The velocity sums (the Laplacian viscosity, with the no-slip walls' term, and XSPH), and a
  // damping zone at the box's far end.
  if (name == "WcsphLaplacianViscosityXsph") {
    auto fixes = wcsph("summation");
    fixes[3].params = {{"kind", std::string("laplacian")}, {"nu", 1e-3}};
    fixes.push_back({"xsph", "xsph", {}});
    fixes.push_back({"zone", "damping", {{"from", Vec3{0.09, 0, 0}}, {"to", Vec3{0.2, 0, 0}}, {"rate", 50.0}}});
    fixes.push_back({"walls", "box", {{"no_slip", true}}});
    return {0.0002, fixes, {}};
  }
  // Sinks on the block's way, each with the flow compute: PBF's from step 5 on, WCSPH's from
  // about step 20 (the block's front layer, at 0.095 m, moves 0.1 mm a step).
  if (name == "PbfOutflow")
    return {0.002,
            {kGravity, {"pbf", "pbf", {}}, kWalls,
             {"drain", "outflow", {{"region", std::string("half_space")}, {"point", Vec3{0.1, 0, 0}}, {"normal", Vec3{1, 0, 0}}}}},
            {{"out", "flow", {{"fix", std::string("drain")}}}}};
  if (name == "WcsphOutflow") {
    auto fixes = wcsph("continuity");
    fixes.push_back(kWalls);
    fixes.push_back({"drain", "outflow", {{"region", std::string("box")}, {"lo", Vec3{0.097, 0, 0}}, {"hi", Vec3{0.2, 0.1, 0.2}}}});
    return {0.0002, fixes, {{"out", "flow", {{"fix", std::string("drain")}}}}};
  }
  // A jet from above into the box (a disc of radius 2 cm facing down, the scene's spacing)
  // and a sink over the floor's far end: PBF's layers enter at steps 1, 11, 21 (0.5 m/s),
  // WCSPH's at steps 1 and 26 (2 m/s), so that a restart at step 15 falls between two.
  if (name == "PbfEmitter" || name == "WcsphEmitter") {
    const bool pbf = name == "PbfEmitter";
    std::vector<StyleSpec> fixes = pbf ? std::vector<StyleSpec>{kGravity, {"pbf", "pbf", {}}} : wcsph("continuity");
    fixes.push_back(kWalls);
    fixes.push_back({"jet",
                     "emitter",
                     {{"shape", std::string("disc")}, {"center", Vec3{0.15, 0.05, 0.15}}, {"normal", Vec3{0, 0, -1}},
                      {"radius", 0.02}, {"speed", pbf ? 0.5 : 2.0}}});
    fixes.push_back({"drain", "outflow", {{"region", std::string("box")}, {"lo", Vec3{0.17, 0, 0}}, {"hi", Vec3{0.2, 0.1, 0.03}}}});
    return {pbf ? 0.002 : 0.0002, fixes, {{"in", "flow", {{"fix", std::string("jet")}}}}};
  }
  // The same jet through a rectangle 4 x 2 cm, its velocity a function of time and place
  // (the sites' particles enter at different steps) and an inlet zone that takes it.
  if (name == "PbfEmitterFunction") {
    const SpaceTimeFunctionPtr inflow = std::make_shared<GrowingProfile>();
    return {0.002,
            {kGravity,
             {"pbf", "pbf", {}},
             kWalls,
             {"jet",
              "emitter",
              {{"center", Vec3{0.15, 0.05, 0.15}}, {"normal", Vec3{0, 0, -1}}, {"size", Vec2{0.04, 0.02}},
               {"velocity", inflow}, {"buffer", 0.02}}}},
            {{"in", "flow", {{"fix", std::string("jet")}}}}};
  }
  if (name == "PbfFloatingBody")  // a box the block runs into, spinning as it is released, on a stretched spring
    return {0.002,
            {kGravity,
             {"pbf", "pbf", {}},
             kWalls,
             crate({{"velocity", Vec3{0, 0, 0.05}}, {"hold", 0.003}}),
             {"line",
              "spring",
              {{"body", std::string("crate")},
               {"at", Vec3{0.14, 0.05, 0.07}},
               {"to", Vec3{0.19, 0.05, 0.19}},
               {"stiffness", 20.0},
               {"damping", 0.1},
               {"length", 0.1}}}},
            {{"state", "body", {{"solid", std::string("crate")}}}}};
  if (name == "DfsphCflLaplacianViscosity")  // both solves, a Laplacian viscosity, steps the cfl fix chooses
    return {0.002,
            {kGravity,
             {"dfsph", "dfsph", {}},
             {"viscosity", "sph_viscosity", {{"kind", std::string("laplacian")}, {"nu", 1e-3}}},
             {"cfl", "cfl", {{"courant", 0.4}}},
             kWalls},
            {}};
  if (name == "DfsphMovingSolidFloatingBody")  // a paddle pushing the block into a floating crate
    return {0.001,
            {kGravity, {"dfsph", "dfsph", {{"divergence_error", 1e-4}}}, kWalls, paddle(0.006, 0.003, 0.012, 0.005),
             crate({})},
            {{"state", "body", {{"solid", std::string("crate")}}}}};
  if (name == "WcsphHingedFlap") {  // a flap hinged above the floor (clear of it: its contact), turning
    auto fixes = wcsph("summation");
    fixes.push_back(kWalls);
    fixes.push_back({"flap",
                     "solid",
                     {{"shape", std::string("box")},
                      {"lo", Vec3{0.13, 0, 0.025}},
                      {"hi", Vec3{0.14, 0.1, 0.1}},
                      {"density", 800.0},
                      {"free_rotation", Vec3{0, 1, 0}},
                      {"hinge", Vec3{0.135, 0.05, 0.025}},
                      {"angular_velocity", Vec3{0, 2, 0}}}});  // turning from the start
    fixes.push_back({"ball",  // a ball on a ball joint above it, which the water and the flap swing
                     "solid",
                     {{"shape", std::string("sphere")},
                      {"center", Vec3{0.17, 0.045, 0.05}},
                      {"radius", 0.015},
                      {"density", 600.0},
                      {"ball_joint", Vec3{0.172, 0.05, 0.12}}}});
    return {0.0002,
            fixes,
            {{"state", "body", {{"solid", std::string("flap")}}}, {"ball_state", "body", {{"solid", std::string("ball")}}}}};
  }
  ADD_FAILURE() << "no pipeline " << name;
  return {};
}

// Every pipeline above, for the tests that run them all (::testing::ValuesIn).
inline const std::vector<const char*> kPipelines = {
    "PbfVorticityXsph", "WcsphSummationLeapfrogArtificialViscosity", "WcsphContinuityCfl", "PbfSolid", "WcsphMovingSolid",
    "SampleProbesGauge", "WcsphLaplacianViscosityXsph", "PbfOutflow", "WcsphOutflow", "PbfEmitter", "WcsphEmitter",
    "PbfEmitterFunction", "PbfFloatingBody", "WcsphHingedFlap", "DfsphCflLaplacianViscosity",
    "DfsphMovingSolidFloatingBody"};

// A block of 10 x 10 x 8 particles (spacing 1 cm, h = 2 cm) moving at 0.5 m/s along x, in
// a box twice as long.
inline void make_scene(Simulation& sim, double dt) {
  sim.set_domain(Domain{{0, 0, 0}, {0.2, 0.1, 0.2}});
  sim.set_kernel_radius(0.02);
  sim.set_timestep(dt);
  const double lo[3] = {0, 0, 0}, hi[3] = {0.1, 0.1, 0.08}, v[3] = {0.5, 0, 0};
  add_lattice(sim, lo, hi, 0.01, v);
}

inline void add(Simulation& sim, const Pipeline& p) {
  const auto& styles = StyleRegistry::builtin();
  for (const auto& f : p.fixes) sim.add_fix(styles.make_fix(f.id, f.style, f.params));
  for (const auto& c : p.computes) sim.add_compute(styles.make_compute(c.id, c.style, c.params));
}

// Every field of `b` equals the same-named field of `a` bit for bit, particle by particle in
// memory order (a continued run keeps the straight run's order), and both have the same fields.
inline void expect_same_fields(const Particles& a, const Particles& b) {
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(std::memcmp(a.ids(), b.ids(), a.size() * sizeof(*a.ids())), 0) << "memory order differs";
  EXPECT_EQ(a.fields().size(), b.fields().size());
  for (FieldId f : a.fields()) {
    const auto& spec = a.spec(f);
    const auto other = b.find(spec.name);
    ASSERT_TRUE(other) << "the continued run has no field '" << spec.name << "'";
    for (int c = 0; c < spec.components; ++c)
      for (std::size_t i = 0; i < a.size(); ++i)
        ASSERT_EQ(std::memcmp(a.data(f, c) + i, b.data(*other, c) + i, sizeof(real)), 0)
            << "field '" << spec.name << "' component " << c << " of particle " << i << ": " << a.data(f, c)[i]
            << " straight, " << b.data(*other, c)[i] << " continued";
  }
}

}  // namespace pbf::test
