// Style parameters are checked against each style's schema when a fix or compute is made.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "engine/core/error.hpp"
#include "engine/registry/style_registry.hpp"

using namespace pbf;

namespace {

std::string error_of(const std::string& style, const GivenParams& given) {
  try {
    StyleRegistry::builtin().make_fix("f", style, given);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(Params, UnknownStyleListsTheValidOnes) {
  const std::string e = error_of("gravityy", {});
  EXPECT_NE(e.find("unknown fix style 'gravityy'"), std::string::npos) << e;
  EXPECT_NE(e.find("pbf"), std::string::npos) << e;
  EXPECT_NE(e.find("dump/text"), std::string::npos) << e;
}

TEST(Params, UnknownParameterListsTheValidOnes) {
  const std::string e = error_of("pbf", {{"iteration", std::int64_t{3}}});
  EXPECT_NE(e.find("fix 'f' (pbf): unknown parameter 'iteration'"), std::string::npos) << e;
  EXPECT_NE(e.find("iterations"), std::string::npos) << e;
  EXPECT_NE(e.find("scorr_k"), std::string::npos) << e;
}

TEST(Params, IllTypedValuesAreRefused) {
  EXPECT_NE(error_of("pbf", {{"iterations", std::string("four")}}).find("must be of type integer"), std::string::npos);
  EXPECT_NE(error_of("pbf", {{"iterations", 2.5}}).find("'iterations'"), std::string::npos);
  EXPECT_NE(error_of("gravity", {{"acceleration", 9.81}}).find("must be of type vector"), std::string::npos);
  EXPECT_NE(error_of("pbf", {{"one_sided", std::int64_t{1}}}).find("must be of type boolean"), std::string::npos);
  EXPECT_NE(error_of("dump/text", {{"path", 3.0}}).find("must be of type string"), std::string::npos);
}

TEST(Params, IntegralNumbersAreIntegersAndIntegersAreNumbers) {
  EXPECT_EQ(error_of("pbf", {{"iterations", 3.0}}), "");
  EXPECT_EQ(error_of("xsph", {{"c", std::int64_t{0}}}), "");
}

TEST(Params, RangeChecksNameTheFix) {
  const std::string e = error_of("pbf", {{"iterations", std::int64_t{0}}});
  EXPECT_NE(e.find("fix 'f' (pbf): parameter 'iterations' must be in [1, 1000], got 0"), std::string::npos) << e;
  EXPECT_NE(error_of("pbf", {{"epsilon", 0.0}}).find("parameter 'epsilon' must be > 0 S0, got 0"), std::string::npos);
  EXPECT_NE(error_of("gravity", {{"acceleration", Vec3{0, 0, -1e300}}}).find("must be in [-10000, 10000] m/s^2"),
            std::string::npos);
  EXPECT_NE(error_of("wcsph", {{"eos", std::string("tiat")}})
                .find("parameter 'eos' must be one of \"tait\" or \"linear\", got \"tiat\" (did you mean 'tait'?)"),
            std::string::npos);
  EXPECT_NE(error_of("dump/text", {}).find("exactly one of 'interval'"), std::string::npos);
  EXPECT_NE(error_of("box", {{"restitution", 1.5}}).find("restitution"), std::string::npos);
}

TEST(Params, NonFiniteValuesAreRefused) {
  EXPECT_NE(error_of("xsph", {{"c", std::nan("")}}).find("finite"), std::string::npos);
}

TEST(Params, DefaultsFillWhatIsNotGiven) {
  const StyleInfo* info = StyleRegistry::builtin().find("pbf");
  ASSERT_NE(info, nullptr);
  Params p("pbf", info->params, {{"iterations", std::int64_t{7}}});
  EXPECT_EQ(p.integer("iterations"), 7);
  EXPECT_DOUBLE_EQ(p.real("epsilon"), 0.01);
  EXPECT_TRUE(p.boolean("one_sided"));
}

TEST(Params, HelpListsEveryStyleAndEveryParameter) {
  const auto& r = StyleRegistry::builtin();
  const std::string all = r.help();
  for (const auto& s : r.styles()) {
    EXPECT_NE(all.find(s.name), std::string::npos) << s.name;
    const std::string one = r.help(s.name);
    for (const auto& p : s.params) EXPECT_NE(one.find(p.name), std::string::npos) << s.name << "." << p.name;
  }
  EXPECT_THROW(r.help("no_such_style"), Error);
}

// A style's defaults must pass its own checks: a default outside its range would make the
// style unusable without that parameter. (A required parameter gets a plain value of its type.)
TEST(Params, EveryDefaultIsInItsRange) {
  for (const auto& s : StyleRegistry::builtin().styles()) {
    GivenParams defaults;
    for (const auto& p : s.params) {
      if (p.default_value) defaults.emplace_back(p.name, *p.default_value);
      if (!p.default_value && !p.optional) {
        if (p.type == ParamType::String)  // a name, or the first of its choices
          defaults.emplace_back(p.name, p.choices.empty() ? std::string("name") : p.choices.front());
        else if (p.type == ParamType::StringList) defaults.emplace_back(p.name, Names{"name"});
        else if (p.type == ParamType::PointList) defaults.emplace_back(p.name, Points{{0, 0, 0}});
        else if (p.type == ParamType::Real) defaults.emplace_back(p.name, 1.0);
        else if (p.type == ParamType::Vector3) defaults.emplace_back(p.name, Vec3{0, 0, 0});
        else FAIL() << s.name << "." << p.name << ": give this test a value of its type";
      }
    }
    EXPECT_NO_THROW(Params(s.name, s.params, defaults)) << s.name;
  }
}

TEST(Params, StylesReferenceInDocsIsCurrent) {
  // docs/styles.md holds the output of `pbfengine help --markdown`; regenerate it when a
  // style or parameter changes.
  std::ifstream in(std::string(PBF_SOURCE_DIR) + "/docs/styles.md");
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_NE(text.str().find(StyleRegistry::builtin().markdown_reference()), std::string::npos)
      << "docs/styles.md is stale: regenerate it with build/pbfengine help --markdown";
}
