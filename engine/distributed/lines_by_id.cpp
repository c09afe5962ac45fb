#include "engine/distributed/lines_by_id.hpp"

#include <cstring>
#include <fmt/format.h>
#include <vector>

#include "engine/core/error.hpp"
#include "engine/distributed/comm.hpp"
#include "engine/distributed/id_blocks.hpp"

namespace pbf {

namespace {

template <class T>
void put(std::vector<char>& out, T value) {
  const char* bytes = reinterpret_cast<const char*>(&value);
  out.insert(out.end(), bytes, bytes + sizeof value);
}

}  // namespace

void write_lines_by_id(const std::string& path, const std::string& head, std::size_t total,
                       std::span<const std::int64_t> ids, std::span<const char> text,
                       std::span<const std::size_t> ends) {
  const int R = comm::ranks(), me = comm::rank();
  // Each line, as (id, length, bytes), to the rank of its block.
  std::vector<std::vector<char>> send(static_cast<std::size_t>(R));
  for (std::size_t k = 0; k < ids.size(); ++k) {
    const std::size_t begin = k ? ends[k - 1] : 0, length = ends[k] - begin;
    if (ids[k] < 0 || static_cast<std::size_t>(ids[k]) >= total)
      throw Error(fmt::format("{}: particle id {} outside 0..{}", path, ids[k], total - 1));
    auto& out = send[static_cast<std::size_t>(id_block_of(static_cast<std::size_t>(ids[k]), total, R))];
    put(out, ids[k]);
    put(out, static_cast<std::int64_t>(length));
    out.insert(out.end(), text.begin() + static_cast<std::ptrdiff_t>(begin),
               text.begin() + static_cast<std::ptrdiff_t>(begin + length));
  }
  std::vector<std::vector<char>> received;
  comm::all_to_all_bytes(send, received);
  send.clear();
  // This rank's block in id order.
  const std::size_t first = id_block_begin(total, me, R), count = id_block_begin(total, me + 1, R) - first;
  std::vector<const char*> line(count, nullptr);
  std::vector<std::int64_t> length(count, 0);
  std::size_t bytes = me == 0 ? head.size() : 0;
  for (const auto& from : received)
    for (std::size_t at = 0; at < from.size();) {
      std::int64_t id = 0, n = 0;
      std::memcpy(&id, from.data() + at, sizeof id);
      std::memcpy(&n, from.data() + at + sizeof id, sizeof n);
      at += sizeof id + sizeof n;
      const std::size_t slot = static_cast<std::size_t>(id) - first;
      if (line[slot]) throw Error(fmt::format("{}: particle id {} held by two ranks", path, id));
      line[slot] = from.data() + at;
      length[slot] = n;
      bytes += static_cast<std::size_t>(n);
      at += static_cast<std::size_t>(n);
    }
  std::vector<char> block;
  block.reserve(bytes);
  if (me == 0) block.insert(block.end(), head.begin(), head.end());
  for (std::size_t k = 0; k < count; ++k) {
    if (!line[k]) throw Error(fmt::format("{}: no rank holds particle id {}", path, first + k));
    block.insert(block.end(), line[k], line[k] + length[k]);
  }
  comm::write_file(path, comm::exclusive_sum(static_cast<std::int64_t>(block.size())), block);
}

}  // namespace pbf
