#include "engine/distributed/lines_by_id.hpp"

#include <algorithm>
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

void write_lines_by_id(const std::string& path, const std::string& head, std::int64_t next_id,
                       std::span<const std::int64_t> ids, std::span<const char> text,
                       std::span<const std::size_t> ends) {
  const int R = comm::ranks();
  const IdBlocks blocks(ids, next_id);
  // Each line, as (id, length, bytes), to the rank of its block.
  std::vector<std::vector<char>> send(static_cast<std::size_t>(R));
  for (std::size_t k = 0; k < ids.size(); ++k) {
    const std::size_t begin = k ? ends[k - 1] : 0, length = ends[k] - begin;
    auto& out = send[static_cast<std::size_t>(blocks.rank_of(ids[k]))];
    put(out, ids[k]);
    put(out, static_cast<std::int64_t>(length));
    out.insert(out.end(), text.begin() + static_cast<std::ptrdiff_t>(begin),
               text.begin() + static_cast<std::ptrdiff_t>(begin + length));
  }
  std::vector<std::vector<char>> received;
  comm::all_to_all_bytes(send, received);
  send.clear();
  // This rank's block in id order.
  struct Line {
    std::int64_t id, length;
    const char* bytes;
  };
  std::vector<Line> lines;
  std::size_t bytes = comm::root() ? head.size() : 0;
  for (const auto& from : received)
    for (std::size_t at = 0; at < from.size();) {
      Line line{0, 0, nullptr};
      std::memcpy(&line.id, from.data() + at, sizeof line.id);
      std::memcpy(&line.length, from.data() + at + sizeof line.id, sizeof line.length);
      at += sizeof line.id + sizeof line.length;
      line.bytes = from.data() + at;
      lines.push_back(line);
      bytes += static_cast<std::size_t>(line.length);
      at += static_cast<std::size_t>(line.length);
    }
  std::sort(lines.begin(), lines.end(), [](const Line& a, const Line& b) { return a.id < b.id; });
  for (std::size_t k = 1; k < lines.size(); ++k)
    if (lines[k].id == lines[k - 1].id) throw Error(fmt::format("{}: particle id {} held by two ranks", path, lines[k].id));
  std::vector<char> block;
  block.reserve(bytes);
  if (comm::root()) block.insert(block.end(), head.begin(), head.end());
  for (const Line& line : lines) block.insert(block.end(), line.bytes, line.bytes + line.length);
  comm::write_file(path, comm::exclusive_sum(static_cast<std::int64_t>(block.size())), block);
}

}  // namespace pbf
