#include "engine/core/names.hpp"

#include <algorithm>
#include <cctype>

namespace pbf {

namespace {

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// Damerau-Levenshtein distance in its "optimal string alignment" form: the edits are
// insertion, deletion, substitution and the swap of two neighbours, the usual typos.
std::size_t edit_distance(const std::string& a, const std::string& b) {
  const std::size_t n = a.size(), m = b.size();
  // d[i][j]: distance between the first i characters of a and the first j of b.
  std::vector<std::vector<std::size_t>> d(n + 1, std::vector<std::size_t>(m + 1));
  for (std::size_t i = 0; i <= n; ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= m; ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= n; ++i)
    for (std::size_t j = 1; j <= m; ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[n][m];
}

}  // namespace

std::string nearest_name(const std::string& name, const std::vector<std::string>& valid) {
  // Two edits catch nearly every typo; the half-length bound keeps short names (a 3-letter
  // name is two edits from most 3-letter names) from suggesting something unrelated.
  const std::string key = lower(name);
  std::string best;
  std::size_t best_distance = 3;
  for (const auto& candidate : valid) {
    const std::size_t d = edit_distance(key, lower(candidate));
    if (d < best_distance && 2 * d < name.size()) {
      best = candidate;
      best_distance = d;
    }
  }
  return best;
}

std::string did_you_mean(const std::string& name, const std::vector<std::string>& valid) {
  const std::string nearest = nearest_name(name, valid);
  return nearest.empty() ? "" : " (did you mean '" + nearest + "'?)";
}

}  // namespace pbf
