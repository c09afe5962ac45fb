#pragma once
// Fix and compute styles by name, each with its parameter schema. The schema checks a
// script's parameters, and produces `pbfengine help` and the scripting reference.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "engine/core/compute.hpp"
#include "engine/core/fix.hpp"
#include "engine/registry/params.hpp"

namespace pbf {

enum class StyleKind { fix, compute };

struct StyleInfo {
  std::string name;
  StyleKind kind;
  std::string summary;  // one line
  std::vector<ParamSpec> params;
  std::function<std::unique_ptr<Fix>(const std::string& id, const Params&)> make_fix;
  std::function<std::unique_ptr<Compute>(const std::string& id, const Params&)> make_compute;
  // A compute's values and their units, for the help and the reference (`name` in backticks):
  // each instance's Compute::units() must appear in it (tests/test_probe.cpp checks).
  std::string values = {};
};

class StyleRegistry {
 public:
  // The registry holding every built-in style.
  static const StyleRegistry& builtin();

  void add(StyleInfo info);
  const StyleInfo* find(const std::string& name) const;
  const std::vector<StyleInfo>& styles() const { return styles_; }

  // Validate the parameters, then construct. Errors list the valid styles or parameters.
  std::unique_ptr<Fix> make_fix(const std::string& id, const std::string& style, const GivenParams& given) const;
  std::unique_ptr<Compute> make_compute(const std::string& id, const std::string& style,
                                        const GivenParams& given) const;

  std::string help() const;                          // one line per style
  std::string help(const std::string& style) const;  // its parameters; throws if unknown
  std::string markdown_reference() const;            // docs/reference

 private:
  const StyleInfo& require(const std::string& style, StyleKind kind) const;
  std::vector<StyleInfo> styles_;
};

// The one explicit list of built-in styles (engine/builtin_styles.cpp).
void register_builtin_styles(StyleRegistry& registry);

}  // namespace pbf
