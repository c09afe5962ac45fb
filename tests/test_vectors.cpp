// The pair loops give the same bits at every vector width the machine offers (AVX-512, AVX2,
// SSE4, none): each sum over a particle's neighbours groups its terms in the same lanes and
// adds them in the same tree whatever the width (docs/design.md, "Vectors"). The dam break
// (PBF with vorticity and XSPH, and WCSPH) is run at each width and its final frame compared
// byte for byte; and an unknown width is refused by name.
#include <gtest/gtest.h>

#include <string>

#include "engine/core/vectors.hpp"
#include "test_util.hpp"

using pbf::test::read_file;
using pbf::test::run_engine;
using pbf::test::scenario;

namespace {

std::string final_frame(const std::string& solver, const std::string& vectors) {
  const auto dir = pbf::test::temp_dir("vectors-" + solver + "-" + vectors);
  auto r = run_engine("run " + scenario("dambreak.lua") + " -v solver=" + solver +
                      " -v particles=2000 -v t_end=0.1 -v interval=0.1 -v restart_interval=0 -v out=" +
                      dir.string() + " --threads 2 --vectors " + vectors);
  EXPECT_EQ(r.code, 0) << r.output;
  return read_file(dir / "frame_00001.txt");
}

TEST(Vectors, EveryWidthGivesTheSameBits) {
  const auto choices = pbf::vector_choices();
  ASSERT_FALSE(choices.empty());
  EXPECT_EQ(choices.back(), "none");  // the version without vectors is always there
  for (const std::string solver : {"pbf", "wcsph"}) {
    const std::string widest = final_frame(solver, "auto");
    ASSERT_GT(widest.size(), 2000u * 6 * 4) << solver;
    for (const auto& choice : choices)
      EXPECT_TRUE(final_frame(solver, choice) == widest) << solver << " with vectors '" << choice
                                                         << "' differs from the widest";
  }
}

TEST(Vectors, AnUnknownWidthIsRefusedByName) {
  auto r = run_engine("run " + scenario("dambreak.lua") + " --vectors avx1024");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("--vectors: 'avx1024' is not one of this machine's choices: auto"), std::string::npos)
      << r.output;
}

}  // namespace
