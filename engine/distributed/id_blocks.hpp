#pragma once
// Blocks of ids: rank r of R writes the particles with ids [r N / R, (r + 1) N / R) of a file in
// id order (text frames, restarts), whichever rank owns them.
#include <cstdint>

namespace pbf {

inline std::uint64_t id_block_begin(std::uint64_t total, int rank, int ranks) {
  return static_cast<std::uint64_t>(static_cast<unsigned __int128>(total) * static_cast<unsigned>(rank) /
                                    static_cast<unsigned>(ranks));
}

// The rank whose block holds `id` (id < total).
inline int id_block_of(std::uint64_t id, std::uint64_t total, int ranks) {
  int r = static_cast<int>(static_cast<unsigned __int128>(id) * static_cast<unsigned>(ranks) / total);
  while (r + 1 < ranks && id_block_begin(total, r + 1, ranks) <= id) ++r;
  while (r > 0 && id_block_begin(total, r, ranks) > id) --r;
  return r;
}

}  // namespace pbf
