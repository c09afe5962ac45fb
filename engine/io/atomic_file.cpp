#include "engine/io/atomic_file.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fmt/format.h>

#include "engine/core/error.hpp"

namespace pbf {

AtomicFile::AtomicFile(const std::string& path) : path_(path), tmp_(path + ".tmp") {
  file_ = std::fopen(tmp_.c_str(), "wb");
  if (!file_) fail("cannot create", errno);
}

AtomicFile::~AtomicFile() {
  if (file_) {
    std::fclose(file_);
    std::remove(tmp_.c_str());
  }
}

void AtomicFile::write(const void* data, std::size_t bytes) {
  if (bytes && std::fwrite(data, 1, bytes, file_) != bytes) fail("cannot write", errno);
}

void AtomicFile::commit() {
  std::FILE* f = file_;
  file_ = nullptr;
  if (std::fclose(f) != 0) {
    const int err = errno;
    std::remove(tmp_.c_str());
    fail("cannot write", err);
  }
  std::error_code ec;
  std::filesystem::rename(tmp_, path_, ec);
  if (ec) {
    std::remove(tmp_.c_str());
    throw Error(fmt::format("{}: cannot rename {} onto it: {}", path_, tmp_, ec.message()));
  }
}

void AtomicFile::fail(const char* what, int err) const {
  throw Error(fmt::format("{}: {} {}: {}", path_, what, tmp_, std::strerror(err)));
}

}  // namespace pbf
