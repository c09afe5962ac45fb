#include "scripting/log_file.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <mutex>

namespace pbf::log_file {

namespace {
std::mutex mutex;  // spdlog may log from OpenMP threads
std::FILE* file = nullptr;
}  // namespace

std::string open(const std::string& path) {
  std::lock_guard<std::mutex> lock(mutex);
  if (file) std::fclose(file);
  file = std::fopen(path.c_str(), "we");  // 'e': close-on-exec, so ffmpeg (dump/movie) does not inherit it
  return file ? "" : std::strerror(errno);
}

void write(std::string_view text) {
  std::lock_guard<std::mutex> lock(mutex);
  if (!file) return;
  std::fwrite(text.data(), 1, text.size(), file);
  std::fflush(file);
}

bool close() {
  std::lock_guard<std::mutex> lock(mutex);
  if (!file) return true;
  const bool ok = !std::ferror(file);
  const bool closed = std::fclose(file) == 0;
  file = nullptr;
  return ok && closed;
}

}  // namespace pbf::log_file
