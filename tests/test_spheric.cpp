// scenarios/spheric_dambreak.lua (SPHERIC Test 2, docs/validation/spheric.md), run very
// coarse (spacing 0.1 m: 780 particles) for 0.3 s with each solver: it runs without error,
// writes OUT/probes.csv with the pressure probes P1-P8 and the four gauges, the reservoir
// gauge reads the column's 0.55 m at t = 0 within a spacing and has started to fall by
// 0.3 s, and the gauges in front of the column are dry at t = 0. Cheap: well under a second
// per solver.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "test_util.hpp"

using pbf::test::run_engine;
using pbf::test::scenario;

namespace {


}  // namespace

class Spheric : public ::testing::TestWithParam<std::string> {};

TEST_P(Spheric, CoarseRunWritesProbesAndGauges) {
  const std::string solver = GetParam();
  const auto dir = pbf::test::temp_dir("spheric-" + solver);
  auto r = run_engine("run " + scenario("spheric_dambreak.lua") + " -v solver=" + solver +
                      " -v spacing=0.1 -v t_end=0.3 -v out=" + (dir / "out").string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(r.output.find("warning"), std::string::npos) << r.output;
  std::vector<std::string> names;
  auto c = pbf::test::read_csv(dir / "out" / "probes.csv", &names);
  ASSERT_FALSE(names.empty());
  EXPECT_EQ(names.front(), "time");
  for (const char* col : {"P.P1", "P.P2", "P.P3", "P.P4", "P.P5", "P.P6", "P.P7", "P.P8", "H.x0496", "H.x0992",
                          "H.x1488", "H.x2638"})
    ASSERT_TRUE(c.count(col)) << "no column " << col << " in probes.csv";
  const auto& t = c["time"];
  ASSERT_GT(t.size(), 10u);
  EXPECT_NEAR(t.front(), 0.0, 0.03);
  EXPECT_GT(t.back(), 0.29);
  const double s = 0.55 / 6;  // the scenario's spacing: 0.1 m rounded to whole layers in 0.55 m
  EXPECT_NEAR(c["H.x2638"].front(), 0.55, s);
  EXPECT_LT(c["H.x2638"].back(), c["H.x2638"].front());  // the reservoir empties
  for (const char* g : {"H.x0496", "H.x0992", "H.x1488"}) EXPECT_EQ(c[g].front(), 0.0) << g;
  for (const auto& [name, values] : c)
    for (double v : values) ASSERT_TRUE(std::isfinite(v)) << name;
}

INSTANTIATE_TEST_SUITE_P(BothSolvers, Spheric, ::testing::Values("pbf", "wcsph"));
