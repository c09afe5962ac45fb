#pragma once
// One text file with a line per particle in id order, written by every rank of a distributed
// run together: no rank holds more than its share of the lines. Each rank formats the lines of
// its own particles; each line goes to the rank that writes its block of ids
// (engine/distributed/id_blocks.hpp); each rank writes its block at its offset in the file
// (MPI-IO). The file has the same bytes as one process writing every line in id order.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

namespace pbf {

// `head` (rank 0's) comes first; then every particle's line in ascending id order: line k of
// this rank is text[ends[k - 1] .. ends[k]) (ends[-1] = 0), the line of particle ids[k];
// next_id bounds the ids. Collective.
void write_lines_by_id(const std::string& path, const std::string& head, std::int64_t next_id,
                       std::span<const std::int64_t> ids, std::span<const char> text,
                       std::span<const std::size_t> ends);

}  // namespace pbf
