#include "engine/output/path_pattern.hpp"

#include <algorithm>
#include <filesystem>
#include <fmt/format.h>

#include "engine/core/error.hpp"

namespace pbf {

PathPattern::PathPattern(std::string pattern, const char* star) : pattern_(std::move(pattern)) {
  if (std::count(pattern_.begin(), pattern_.end(), '*') != 1)
    throw Error(fmt::format("parameter 'path' must contain one '*' (replaced by {}), got '{}'", star, pattern_));
}

std::string PathPattern::with(const std::string& text) const {
  const auto star = pattern_.find('*');
  return pattern_.substr(0, star) + text + pattern_.substr(star + 1);
}

void PathPattern::create_directory() const { create_parent_directory(pattern_); }

void create_parent_directory(const std::string& path) {
  const auto dir = std::filesystem::path(path).parent_path();
  if (dir.empty()) return;
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (!std::filesystem::is_directory(dir)) throw Error(fmt::format("cannot create the directory '{}'", dir.string()));
}

std::string PathPattern::stem(const std::string& fallback) const {
  std::string s = std::filesystem::path(pattern_).filename().string();
  s = s.substr(0, s.find('*'));
  while (!s.empty() && (s.back() == '_' || s.back() == '-' || s.back() == '.')) s.pop_back();
  return s.empty() ? fallback : s;
}

}  // namespace pbf
