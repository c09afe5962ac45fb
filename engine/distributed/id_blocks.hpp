#pragma once
// Blocks of ids for the files every rank of a distributed run writes together in id order
// (text frames, restarts): rank r writes the particles whose ids lie in [begin(r), begin(r+1)),
// whichever rank owns them. Ids have gaps (removed particles' ids are never given again), so
// the bounds are not r N / R: a histogram of the ids present, 64 bins a rank over
// 0..next_id-1, summed over the ranks, puts the bounds on bin edges that split the particles
// about evenly. Where the bounds fall only decides which rank writes which bytes of the file,
// never the bytes.
#include <cstdint>
#include <span>
#include <vector>

namespace pbf {

class IdBlocks {
 public:
  // From every rank's ids (each id on one rank) and the next id to give. Collective.
  IdBlocks(std::span<const std::int64_t> ids, std::int64_t next_id);
  int ranks() const { return static_cast<int>(counts_.size()); }
  // The rank whose block holds `id`.
  int rank_of(std::int64_t id) const;
  // The particles in rank r's block, and in the blocks before it (every rank knows them all).
  std::uint64_t count(int r) const { return counts_[static_cast<std::size_t>(r)]; }
  std::uint64_t before(int r) const;
  std::uint64_t total() const { return before(ranks()); }

 private:
  std::vector<std::int64_t> bounds_;   // ranks + 1: block r is [bounds_[r], bounds_[r + 1])
  std::vector<std::uint64_t> counts_;  // one per rank
};

}  // namespace pbf
