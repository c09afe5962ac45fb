#include "engine/io/text_lines.hpp"

#include <algorithm>
#include <filesystem>
#include <fmt/format.h>

#include "engine/core/error.hpp"
#include "engine/distributed/comm.hpp"

namespace pbf {

bool is_data_line(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r");
  return first != std::string::npos && text[first] != '#';
}

TextLines::TextLines(const std::string& path, const std::string& kind) : path_(path) {
  // An ifstream opens a directory and fails only at its first read; a device or a pipe may
  // never end (/dev/zero) or block the open (a FIFO): say what the path is instead.
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (std::filesystem::is_directory(status))
    throw Error(fmt::format("{}: cannot open {}: it is a directory", path, kind), true);
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status))
    throw Error(fmt::format("{}: cannot open {}: it is not a regular file (a device, a pipe or a socket)", path, kind),
                true);
  in_.open(path, std::ios::binary);
  if (!in_) throw Error(fmt::format("{}: cannot open {}", path, kind), true);
}

void TextLines::fail(long line, const std::string& message) const {
  throw Error(fmt::format("{}:{}: {}", path_, line, message), true);
}

bool TextLines::next(std::string& text) {
  if (position_ >= end_) return false;
  if (!std::getline(in_, text)) {
    if (in_.bad()) fail(line_ + 1, "cannot read the file");
    return false;
  }
  position_ += text.size() + 1;
  ++line_;
  return true;
}

std::uint64_t TextLines::line_start_at_or_after(std::uint64_t offset, std::uint64_t from, std::uint64_t size) {
  if (offset <= from) return from;
  if (offset >= size) return size;
  in_.clear();
  in_.seekg(static_cast<std::streamoff>(offset - 1));
  for (std::uint64_t at = offset;; ++at) {  // the byte before `at` ends a line: a line starts at `at`
    const int c = in_.get();
    if (c == std::char_traits<char>::eof()) return size;
    if (c == '\n') return at;
  }
}

void TextLines::share_rest() {
  if (!comm::distributed()) return;
  const std::uint64_t from = position_, size = std::filesystem::file_size(path_);
  const auto rest = static_cast<unsigned __int128>(size > from ? size - from : 0);
  const auto rank = static_cast<unsigned __int128>(comm::rank()), ranks = static_cast<unsigned __int128>(comm::ranks());
  const std::uint64_t start = line_start_at_or_after(from + static_cast<std::uint64_t>(rest * rank / ranks), from, size);
  const std::uint64_t end =
      line_start_at_or_after(from + static_cast<std::uint64_t>(rest * (rank + 1) / ranks), from, size);
  // Count the share's lines and data lines, for the numbers of the higher ranks'.
  in_.clear();
  in_.seekg(static_cast<std::streamoff>(start));
  std::int64_t lines = 0, rows = 0;
  enum { blank, comment, data } state = blank;
  bool open_line = false;
  std::string chunk(1 << 20, '\0');
  for (std::uint64_t at = start; at < end;) {
    const auto want = static_cast<std::streamsize>(std::min<std::uint64_t>(chunk.size(), end - at));
    in_.read(chunk.data(), want);
    const std::streamsize got = in_.gcount();
    if (got <= 0) break;
    for (std::streamsize k = 0; k < got; ++k) {
      const char c = chunk[static_cast<std::size_t>(k)];
      open_line = true;
      if (c == '\n') {
        ++lines;
        rows += state == data;
        state = blank;
        open_line = false;
      } else if (state == blank && c != ' ' && c != '\t' && c != '\r') {
        state = c == '#' ? comment : data;
      }
    }
    at += static_cast<std::uint64_t>(got);
  }
  if (open_line) ++lines, rows += state == data;  // the file's last line, without its '\n'
  if (in_.bad()) fail(line_ + 1, "cannot read the file");
  line_ += static_cast<long>(comm::exclusive_sum(lines));
  first_row_ = comm::exclusive_sum(rows);
  in_.clear();
  in_.seekg(static_cast<std::streamoff>(start));
  position_ = start;
  end_ = end;
}

}  // namespace pbf
