#include "engine/core/vectors.hpp"

#include <algorithm>
#include <cstdint>
#include <iterator>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <hwy/highway.h>
#include <hwy/targets.h>

#include "engine/core/error.hpp"

namespace pbf {

namespace {

struct Choice {
  const char* name;
  std::int64_t own;  // Highway's targets of this width
};

// Widest first; a choice allows its own targets and those of every choice after it.
constexpr Choice kChoices[] = {{"avx512", HWY_AVX3 | HWY_AVX3_DL},
                               {"avx2", HWY_AVX2},
                               {"sse4", HWY_SSSE3 | HWY_SSE4},
                               {"none", HWY_EMU128 | HWY_SCALAR}};

// The targets compiled into this binary that the machine runs.
std::int64_t usable() { return hwy::SupportedTargets() & HWY_TARGETS; }

// The best target in `targets` (Highway numbers better targets with lower bits).
std::int64_t best(std::int64_t targets) { return targets & -targets; }

}  // namespace

std::vector<std::string> vector_choices() {
  std::vector<std::string> names;
  for (const Choice& c : kChoices)
    if (usable() & c.own) names.emplace_back(c.name);
  return names;
}

void limit_vectors(const std::string& name) {
  hwy::SetSupportedTargetsForTest(0);  // the machine's own targets again
  if (name == "auto") return;
  const auto names = vector_choices();
  std::int64_t allowed = 0;
  for (auto c = std::rbegin(kChoices); c != std::rend(kChoices); ++c) {
    allowed |= c->own;
    if (name == c->name && std::find(names.begin(), names.end(), name) != names.end()) {
      hwy::SetSupportedTargetsForTest(usable() & allowed);
      return;
    }
  }
  throw Error(fmt::format("'{}' is not one of this machine's choices: auto, {}", name, fmt::join(names, ", ")));
}

std::string vectors_in_use() { return hwy::TargetName(best(usable())); }

}  // namespace pbf
