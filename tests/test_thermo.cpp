// Thermo columns and their units: the console shows a line of units under the names, the CSV
// starts with a "# units:" comment line, every compute style declares a unit per value (and
// its reference lists them), and a labelled single point keeps its label in its column name.
#include <gtest/gtest.h>

#include "engine/core/simulation.hpp"
#include "engine/registry/style_registry.hpp"
#include "test_util.hpp"

using namespace pbf;

namespace {

const StyleRegistry& styles() { return StyleRegistry::builtin(); }

// Parameters that make an instance of each compute style.
GivenParams example_params(const std::string& style) {
  if (style == "load" || style == "body") return {{"solid", std::string("s")}};
  if (style == "flow" || style == "spring_tension") return {{"fix", std::string("drain")}};
  if (style == "probe" || style == "gauge") return {{"points", Points{{0, 0, 0}, {1, 1, 1}}}};
  return {};
}

}  // namespace

TEST(Thermo, EveryComputeStyleDeclaresAUnitPerValue) {
  int computes = 0;
  for (const auto& info : styles().styles()) {
    if (info.kind != StyleKind::compute) continue;
    ++computes;
    std::vector<GivenParams> variants = {example_params(info.name)};
    if (info.name == "probe")
      for (const char* field : {"velocity", "density"}) {
        variants.push_back(example_params("probe"));
        variants.back().push_back({"field", std::string(field)});
      }
    for (const auto& p : variants) {
      const auto c = styles().make_compute("c", info.name, p);
      const auto units = c->units();
      ASSERT_EQ(units.size(), c->names().size()) << info.name;
      EXPECT_EQ(c->columns().size(), c->names().size()) << info.name;
      for (const auto& unit : units) {
        EXPECT_FALSE(unit.empty()) << info.name;
        // The reference says it: "... (m/s)", "... (-, relative to rho0)".
        EXPECT_NE(info.values.find("(" + unit), std::string::npos)
            << info.name << ": " << unit << " in " << info.values;
      }
    }
  }
  EXPECT_EQ(computes, 15);
}

TEST(Thermo, ALabelledSinglePointKeepsItsName) {
  auto columns = [](const std::string& style, GivenParams p) {
    return styles().make_compute("c", style, p)->columns();
  };
  const Points one = {{0, 0, 0}}, two = {{0, 0, 0}, {1, 1, 1}};
  EXPECT_EQ(columns("count", {}), (Names{"c"}));
  EXPECT_EQ(columns("speed", {}), (Names{"c.max", "c.avg"}));
  EXPECT_EQ(columns("probe", {{"points", one}}), (Names{"c"}));
  EXPECT_EQ(columns("probe", {{"points", one}, {"labels", Names{"floor"}}}), (Names{"c.floor"}));
  EXPECT_EQ(columns("probe", {{"points", two}}), (Names{"c.p1", "c.p2"}));
  EXPECT_EQ(columns("probe", {{"points", one}, {"field", std::string("velocity")}}),
            (Names{"c.vx1", "c.vy1", "c.vz1"}));
  EXPECT_EQ(columns("gauge", {{"points", one}}), (Names{"c"}));
  EXPECT_EQ(columns("gauge", {{"points", one}, {"labels", Names{"left"}}}), (Names{"c.left"}));
}

TEST(Thermo, ColumnsSayTheirUnitsOnTheConsoleAndInTheCsv) {
  const test::TempDir dir("thermo-units");
  test::write_file(dir / "a.lua",
                   "pbf.domain{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.1}}\npbf.kernel_radius(0.02)\npbf.timestep(0.001)\n"
                   "pbf.lattice{lo = {0, 0, 0}, hi = {0.06, 0.06, 0.04}, spacing = 0.01}\n"
                   "pbf.fix('pbf', 'pbf', {})\npbf.compute('ke', 'kinetic_energy')\n"
                   "pbf.compute('p', 'probe', {points = {{0.03, 0.03, 0.01}}, labels = {'floor'}})\n"
                   "pbf.compute('g', 'gauge', {points = {{0.03, 0.03, 0}}})\n"
                   "pbf.compute('rho', 'probe', {points = {{0.03, 0.03, 0.01}}, labels = {'floor'}, "
                   "field = 'density'})\n"
                   "print('rho', math.type(pbf.value('rho')))\n"
                   "pbf.thermo{every = 1, columns = {'step', 'time', 'ke', 'p.floor', 'g'}, "
                   "csv = var.dir .. '/t.csv'}\n"
                   "pbf.run(1)\n"
                   "pbf.thermo{every = 1, columns = {'step', 'g'}, csv = var.dir .. '/t.csv'}\npbf.run(1)\n");
  const auto r = test::run_engine("run " + (dir / "a.lua").string() + " -v dir=" + dir.path().string());
  ASSERT_EQ(r.code, 0) << r.output;
  // pbf.value of a compute with one value is a number, whatever its column's name.
  EXPECT_NE(r.output.find("rho\tfloat\n"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("          step          time            ke       p.floor             g\n"
                          "           [-]           [s]           [J]          [Pa]           [m]\n"
                          "             0             0             0"),
            std::string::npos)
      << r.output;
  const std::string csv = test::read_file(dir / "t.csv");
  EXPECT_EQ(csv.rfind("# units: step -, time s, ke J, p.floor Pa, g m\nstep,time,ke,p.floor,g\n0,0,0,", 0), 0u) << csv;
  EXPECT_NE(csv.find("\n1,0.001,"), std::string::npos) << csv;
  // New columns in the same file: their units and names again.
  EXPECT_NE(csv.find("\n# units: step -, g m\nstep,g\n2,"), std::string::npos) << csv;
}
