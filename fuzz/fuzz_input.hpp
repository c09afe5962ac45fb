#pragma once
// What the fuzz targets share. The readers take paths, so each input is written to a file
// of this process's own (fuzzers run side by side, and libFuzzer's -fork/-jobs workers are
// processes of their own). The engine's log is silenced (a warning per input would drown
// libFuzzer's output) and runs on one thread (inputs are small; threads only add noise).
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <omp.h>
#include <spdlog/spdlog.h>
#include <string>
#include <unistd.h>

namespace pbf::fuzz {

// $TMPDIR/pbf-fuzz-PID/NAME, rewritten for every input, removed (with its directory) when
// the process exits normally; a crash leaves it, which is harmless: libFuzzer saves the
// crashing input itself.
class InputFile {
 public:
  explicit InputFile(const std::string& name) {
    dir_ = std::filesystem::temp_directory_path() / ("pbf-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
    path_ = (dir_ / name).string();
    spdlog::set_level(spdlog::level::off);
    omp_set_num_threads(1);
  }
  ~InputFile() {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;

  // Writes the input; failing to is the machine's fault, not the input's: stop.
  const std::string& write(const std::uint8_t* data, std::size_t size) const {
    std::FILE* f = std::fopen(path_.c_str(), "wb");
    const bool ok = f && (size == 0 || std::fwrite(data, 1, size, f) == size);
    if (!f || std::fclose(f) != 0 || !ok) {
      std::perror(path_.c_str());
      std::exit(2);
    }
    return path_;
  }

 private:
  std::filesystem::path dir_;
  std::string path_;
};

// A broken promise of the code under test: libFuzzer reports the abort as a crash and
// saves the input.
inline void check(bool ok, const char* what, const std::string& detail = "") {
  if (ok) return;
  std::fprintf(stderr, "fuzz check failed: %s %s\n", what, detail.c_str());
  std::abort();
}

// Every error of a reader names the file it read.
inline void check_names(const std::exception& e, const std::string& path) {
  check(std::string(e.what()).find(path) != std::string::npos, "the error does not name the file:", e.what());
}

}  // namespace pbf::fuzz
