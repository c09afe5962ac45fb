#include "engine/distributed/id_blocks.hpp"

#include <algorithm>

#include "engine/distributed/comm.hpp"

namespace pbf {

IdBlocks::IdBlocks(std::span<const std::int64_t> ids, std::int64_t next_id) {
  const int R = comm::ranks();
  const std::size_t bins = 64 * static_cast<std::size_t>(R);
  const auto bin_start = [&](std::size_t b) {  // the first id of bin b
    return static_cast<std::int64_t>((static_cast<unsigned __int128>(next_id) * b + bins - 1) / bins);
  };
  std::vector<std::int64_t> histogram(bins, 0);
  for (std::int64_t id : ids)
    ++histogram[static_cast<std::size_t>(static_cast<unsigned __int128>(id) * bins /
                                         static_cast<unsigned __int128>(std::max<std::int64_t>(next_id, 1)))];
  comm::sum(std::span<std::int64_t>(histogram));
  std::int64_t total = 0;
  for (std::int64_t c : histogram) total += c;
  // Block r ends at the first bin edge where the count reaches (r + 1) total / R.
  bounds_.assign(1, 0);
  counts_.clear();
  std::size_t b = 0;
  std::int64_t seen = 0, at_bound = 0;
  for (int r = 0; r < R; ++r) {
    const std::int64_t target = static_cast<std::int64_t>(static_cast<__int128>(total) * (r + 1) / R);
    while (b < bins && (seen < target || r + 1 == R)) seen += histogram[b++];
    bounds_.push_back(r + 1 == R ? next_id : bin_start(b));
    counts_.push_back(static_cast<std::uint64_t>(seen - at_bound));
    at_bound = seen;
  }
}

int IdBlocks::rank_of(std::int64_t id) const {
  const auto above = std::upper_bound(bounds_.begin() + 1, bounds_.end() - 1, id);
  return static_cast<int>(above - (bounds_.begin() + 1));
}

std::uint64_t IdBlocks::before(int r) const {
  std::uint64_t sum = 0;
  for (int k = 0; k < r; ++k) sum += counts_[static_cast<std::size_t>(k)];
  return sum;
}

}  // namespace pbf
