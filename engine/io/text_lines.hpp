#pragma once
// The lines of a text file (CSV, the original scene format), read in turn with their numbers.
// A reader takes its header line by line, then calls share_rest(): from there on it reads only
// this process's share of the data lines. In one process that is all of them; in a distributed
// run, the lines that start in this rank's block of the remaining bytes (a block of 1/ranks),
// so that no rank reads or holds the whole file. The line numbers, and the index of the first
// data line of the share among the file's (a data line is neither blank nor a '#' comment),
// come from the lower ranks' counts, so messages and ids are those of one process.
#include <cstdint>
#include <fstream>
#include <string>

namespace pbf {

class TextLines {
 public:
  // Opens `path`; `kind` names it in messages ("scene file", "the file").
  TextLines(const std::string& path, const std::string& kind);

  // The next line (without its '\n'); false at the end of the file, or of the share.
  bool next(std::string& text);
  // The number (1-based) of the line next() gave last.
  long line() const { return line_; }
  [[noreturn]] void fail(long line, const std::string& message) const;

  // Reads from here on only this process's share of the lines. Collective in a distributed run.
  void share_rest();
  // After share_rest(): the data lines of the lower ranks' shares (0 in one process).
  std::int64_t first_row() const { return first_row_; }

 private:
  std::string path_;
  std::ifstream in_;
  long line_ = 0;
  std::uint64_t position_ = 0, end_ = UINT64_MAX;  // the next line's offset; where the share ends
  std::int64_t first_row_ = 0;
  std::uint64_t line_start_at_or_after(std::uint64_t offset, std::uint64_t from, std::uint64_t size);
};

// Whether a line holds data: neither blank nor a comment ('#' after spaces or tabs).
bool is_data_line(const std::string& text);

}  // namespace pbf
