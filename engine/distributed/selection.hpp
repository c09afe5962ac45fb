#pragma once
// The k-th smallest of values spread over the ranks (a percentile, the surge front), exactly
// the value one process would select from all of them. Collective.
#include <cstddef>
#include <vector>

#include "engine/core/real.hpp"

namespace pbf {

// The k-th smallest (from 0) of every rank's `values` together; `values` is reordered. In one
// process (across_ranks false) std::nth_element. Throws when the ranks hold no k + 1 values.
real nth_smallest(std::vector<real>& values, std::size_t k, bool across_ranks);

}  // namespace pbf
