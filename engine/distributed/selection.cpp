#include "engine/distributed/selection.hpp"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <span>

#include "engine/core/error.hpp"
#include "engine/distributed/comm.hpp"

namespace pbf {

namespace {

// The values' order as unsigned integers of their width: a bisection over the integers
// finds the k-th value in as many rounds as the type has bits.
using Key = std::conditional_t<sizeof(real) == 4, std::uint32_t, std::uint64_t>;
constexpr Key kSign = Key(1) << (8 * sizeof(Key) - 1);

Key key_of(real v) {
  const Key bits = std::bit_cast<Key>(v == 0 ? real(0) : v);  // -0 and +0 as one
  return (bits & kSign) ? ~bits : (bits | kSign);
}

real value_of(Key key) { return std::bit_cast<real>((key & kSign) ? (key & ~kSign) : ~key); }

}  // namespace

real nth_smallest(std::vector<real>& values, std::size_t k, bool across_ranks) {
  if (!across_ranks) {
    if (k >= values.size()) throw Error("nth_smallest: too few values");
    std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
    return values[k];
  }
  std::vector<Key> keys(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) keys[i] = key_of(values[i]);
  std::sort(keys.begin(), keys.end());
  // The smallest key with more than k keys at or below it, over all ranks.
  Key lo = 0, hi = ~Key(0);
  if (comm::sum(static_cast<std::int64_t>(keys.size())) <= static_cast<std::int64_t>(k))
    throw Error("nth_smallest: too few values");
  while (lo < hi) {
    const Key mid = lo + (hi - lo) / 2;
    const auto at_or_below = static_cast<std::int64_t>(std::upper_bound(keys.begin(), keys.end(), mid) - keys.begin());
    if (comm::sum(at_or_below) > static_cast<std::int64_t>(k)) hi = mid;
    else lo = mid + 1;
  }
  return value_of(lo);
}

}  // namespace pbf
