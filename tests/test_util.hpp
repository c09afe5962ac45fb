#pragma once
// Helpers shared by the tests: run the pbfengine binary, make temporary directories.
#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>
#include <sys/wait.h>

#include <gtest/gtest.h>
#include <spdlog/sinks/ostream_sink.h>
#include <spdlog/spdlog.h>

#include "engine/core/error.hpp"
#include "engine/core/real.hpp"

// ctest prints only a skipped test's name: a test that cannot run in one precision is named,
// in that build, with why (#if PBF_REAL_IS_FLOAT ... TEST(Suite, Name_SkippedInSinglePrecision...)).
#define PBF_IS_FLOAT_float 1
#define PBF_IS_FLOAT_double 0
#define PBF_CAT_(a, b) a##b
#define PBF_CAT(a, b) PBF_CAT_(a, b)
#define PBF_REAL_IS_FLOAT PBF_CAT(PBF_IS_FLOAT_, PBF_REAL)

namespace pbf::test {

struct Result {
  int code;
  std::string output;  // stdout and stderr together
};

// Runs `pbfengine ARGS` (a shell word list) and captures what it prints (by default
// stdout and stderr together). A `run` gets `--log none` unless ARGS choose a log: tests
// run side by side in one directory and must not write the same log.pbfengine.
inline Result run_engine(const std::string& args, const std::string& redirect = "2>&1") {
  const bool chooses_log = args.find(" --log ") != std::string::npos || args.find(" --log=") != std::string::npos;
  const std::string log = args.rfind("run", 0) == 0 && !chooses_log ? " --log none" : "";
  const std::string command = std::string(PBF_BINARY) + " " + args + log + " " + redirect;
  Result r{-1, ""};
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buf;
  std::size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0) r.output.append(buf.data(), n);
  const int status = pclose(pipe);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return r;
}

inline std::string scenario(const std::string& name) { return std::string(PBF_SOURCE_DIR) + "/scenarios/" + name; }

// A fresh, empty directory under the system's temporary directory ($TMPDIR, else /tmp),
// removed with everything in it when the TempDir goes out of scope. Not copyable, and not
// convertible to a path while a temporary, so no test keeps a path to a removed directory.
class TempDir {
 public:
  explicit TempDir(const std::string& name) {
    static std::mt19937_64 rng(std::random_device{}());
    path_ = std::filesystem::temp_directory_path() / ("pbf-test-" + name + "-" + std::to_string(rng() % 1000000000));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  operator const std::filesystem::path&() const& { return path_; }
  operator const std::filesystem::path&() const&& = delete;
  template <class T>
  std::filesystem::path operator/(const T& child) const& {
    return path_ / child;
  }
  template <class T>
  std::filesystem::path operator/(const T& child) const&& = delete;
  std::string string() const& { return path_.string(); }

 private:
  std::filesystem::path path_;
};

inline TempDir temp_dir(const std::string& name) { return TempDir(name); }

inline void write_file(const std::filesystem::path& path, const std::string& text) { std::ofstream(path) << text; }

// The rows of numbers of a text frame (dump/text): '#' lines skipped, then the count line,
// then one row per particle.
inline std::vector<std::vector<double>> read_frame_rows(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::string line;
  std::vector<std::vector<double>> rows;
  bool counted = false;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (!counted) {
      counted = true;
      continue;
    }
    std::istringstream s(line);
    std::vector<double> row;
    double v;
    while (s >> v) row.push_back(v);
    rows.push_back(row);
  }
  return rows;
}

inline std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A run of `pbfengine ARGS` in DIR, its stdout and stderr kept apart (in DIR/stdout and
// DIR/stderr). ARGS are given as they are, so a test chooses the log itself.
struct SplitRun {
  int code;
  std::string out, err;
};
inline SplitRun run_in(const std::filesystem::path& dir, const std::string& args, const std::string& env = "") {
  const std::string command =
      "cd '" + dir.string() + "' && " + env + " " + PBF_BINARY + " " + args + " > stdout 2> stderr";
  const int status = std::system(command.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, read_file(dir / "stdout"), read_file(dir / "stderr")};
}

// What the engine logs while it lives (added to the default logger's sinks).
class LogCapture {
 public:
  LogCapture() : sink_(std::make_shared<spdlog::sinks::ostream_sink_mt>(text_)) {
    spdlog::default_logger()->sinks().push_back(sink_);
  }
  ~LogCapture() {
    auto& sinks = spdlog::default_logger()->sinks();
    sinks.erase(std::remove(sinks.begin(), sinks.end(), sink_), sinks.end());
  }
  std::string text() const { return text_.str(); }
  int count(const std::string& words) const {
    const std::string all = text();
    int found = 0;
    for (auto at = all.find(words); at != std::string::npos; at = all.find(words, at + 1)) ++found;
    return found;
  }

 private:
  std::ostringstream text_;
  std::shared_ptr<spdlog::sinks::ostream_sink_mt> sink_;
};

}  // namespace pbf::test

namespace pbf::test {
// Relative tolerance for results that would be exact but for rounding: a few hundred
// roundings of the particle data's type.
inline constexpr double kRounding = sizeof(pbf::real) == 4 ? 1e-4 : 1e-9;
// The unit roundoff u of the particle data's type: a stored value is exact to u times itself.
inline constexpr double kUnitRoundoff = std::numeric_limits<pbf::real>::epsilon() / 2;
// The message of the pbf::Error that f() throws, or "" if it throws none. Any other
// exception fails the test (a std::bad_alloc would mean an unchecked size).
template <class F>
std::string error_of(F f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not a pbf::Error: " << e.what();
    return e.what();
  }
  return "";
}


// A CSV with a header line (thermo, probes) as columns by name, with the header's names in
// order in `names` when asked; lines before the header that start with '#' are skipped.
inline std::map<std::string, std::vector<double>> read_csv(const std::filesystem::path& path,
                                                         std::vector<std::string>* names = nullptr) {
  std::istringstream in(read_file(path));
  std::string line, name;
  do std::getline(in, line);
  while (in && (line.empty() || line[0] == '#'));
  std::vector<std::string> header;
  for (std::istringstream h(line); std::getline(h, name, ',');) header.push_back(name);
  std::map<std::string, std::vector<double>> columns;
  while (std::getline(in, line)) {
    std::istringstream row(line);
    std::string cell;
    for (std::size_t k = 0; std::getline(row, cell, ',') && k < header.size(); ++k)
      columns[header[k]].push_back(std::stod(cell));
  }
  if (names) *names = header;
  return columns;
}

}  // namespace pbf::test

// `call` throws a pbf::Error whose message names `name` (a file, a parameter) and says `words`.
#define EXPECT_ERROR_NAMING(call, name, words)                                           \
  do {                                                                                   \
    const std::string e_ = pbf::test::error_of([&] { call; });                           \
    EXPECT_NE(e_.find(std::string(name)), std::string::npos) << "message: " << e_;       \
    EXPECT_NE(e_.find(words), std::string::npos) << "message: " << e_;                   \
  } while (0)
