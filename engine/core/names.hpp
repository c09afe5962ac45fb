#pragma once
// "Did you mean": the valid name a misspelt one was probably meant to be, for the "unknown
// X" messages (styles, parameters, thermo columns, dump fields, commands).
#include <string>
#include <vector>

namespace pbf {

// The valid name nearest to `name`, if it is close enough to be a typo of it: at most two
// edits away (insertions, deletions, substitutions, swaps of neighbours; case ignored) and
// fewer edits than half the name's length. "" when none is. Ties go to the first listed.
std::string nearest_name(const std::string& name, const std::vector<std::string>& valid);

// " (did you mean 'NAME'?)" with the nearest valid name, or "" when none is close.
std::string did_you_mean(const std::string& name, const std::vector<std::string>& valid);

}  // namespace pbf
