#pragma once
// A file that appears under its name only when complete: written as PATH.tmp and renamed
// onto PATH by commit(), so a reader (ParaView polling a running simulation, a user after a
// crash or a full disk) never finds half a frame. Every stdio result is checked: a full
// disk shows up in fwrite, or only in fclose when the data sat in stdio's buffer. Without
// commit() (an error was thrown), the temporary file is removed and nothing is left behind.
#include <cstddef>
#include <cstdio>
#include <string>

namespace pbf {

class AtomicFile {
 public:
  explicit AtomicFile(const std::string& path);
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  ~AtomicFile();

  void write(const void* data, std::size_t bytes);
  void write(const std::string& text) { write(text.data(), text.size()); }
  void commit();

 private:
  [[noreturn]] void fail(const char* what, int err) const;
  std::string path_, tmp_;
  std::FILE* file_ = nullptr;
};

}  // namespace pbf
