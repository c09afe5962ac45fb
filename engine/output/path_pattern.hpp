#pragma once
// A file name pattern with one '*' (a frame number, a step number), as the dump styles and
// the restart fix take, and the directory its files go to, created when the output starts.
#include <string>

namespace pbf {

class PathPattern {
 public:
  // `star` says what '*' stands for, in the error when the pattern has none or several.
  PathPattern(std::string pattern, const char* star);
  const std::string& pattern() const { return pattern_; }
  // The file name's part before '*', without a trailing '_', '-' or '.' ("out/frame_*.vtu" ->
  // "frame"), or `fallback` where nothing is left: what names a series' collection.
  std::string stem(const std::string& fallback) const;
  // The pattern with '*' replaced by `text`.
  std::string with(const std::string& text) const;
  // Creates the directory the files go to (and its parents); an error if that fails.
  void create_directory() const;

 private:
  std::string pattern_;
};

// Creates the directory that `path` goes in (and its parents); an error if that fails.
void create_parent_directory(const std::string& path);

}  // namespace pbf
