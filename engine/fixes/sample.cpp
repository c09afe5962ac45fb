// sample: the values of some computes (probes, gauges, anything with named values) as a
// time series, one CSV per fix:
//
//   time,<name>,...        names as thermo addresses them: a compute's id for a single value,
//                          "id.name" for one of several
//   t0,...                 the state the fix starts from (its first run)
//   t,...                  at the end of the first step that reaches each multiple of
//                          `interval` since the fix's start (t, the actual time)
//
// Rows land on one time grid for the whole life of the fix: a second pbf.run continues it
// (no extra row at its start), and so does a run continued from a restart, which keeps the
// grid's origin, the next multiple and the file's length in the fix state. On continuing,
// the file is cut back to that length and appended to, so rows a crashed run wrote after the
// restart go, and the file ends up as a straight run would have written it. Each row is
// flushed when written (rows are rare; a crash keeps them), so the file is whole at finish.
// engine/io/csv reads particle tables only, so the file is written here, every write checked.
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "engine/core/error.hpp"
#include "engine/core/names.hpp"
#include "engine/core/simulation.hpp"
#include "engine/distributed/comm.hpp"
#include "engine/io/bytes.hpp"
#include "engine/registry/builtin_styles.hpp"

namespace pbf {

namespace {

class Sample : public Fix {
 public:
  Sample(const std::string& id, const Params& p)
      : Fix(id, "sample"), computes_(p.names("computes")), interval_(p.real("interval")), path_(p.string("file")) {
    if (computes_.empty()) throw Error("parameter 'computes': name at least one compute");
    if (path_.empty()) throw Error("parameter 'file': give a file name");
    // A path that cannot be written is said now, where the script names it, not at the run.
    // Append mode: a run continued from a restart appends to the file, which must survive.
    const auto parent = std::filesystem::path(path_).parent_path();
    std::error_code ec;
    if (!parent.empty()) std::filesystem::create_directories(parent, ec);
    std::FILE* f = std::fopen(path_.c_str(), "ab");
    if (!f) throw Error(fmt::format("parameter 'file': cannot write '{}': {}", path_, std::strerror(errno)));
    std::fclose(f);
  }
  ~Sample() override {
    if (file_) std::fclose(file_);
  }

  std::vector<Stage> stages() const override { return {Stage::end_of_step}; }
  Role role() const override { return Role::output; }
  // Every rank evaluates the computes (collective); rank 0 writes the file.
  bool runs_distributed() const override { return true; }

  void init(Simulation& sim) override {
    const std::string header = header_line(sim);
    if (!opened_) open(header);
    sim.outputs().wrote(fmt::format("samples of fix '{}' (sample)", id()), path_);
    if (header != header_)
      throw Error(fmt::format("the computes' values changed since '{}' was started ({} now, {} then): sample "
                              "them into a new file",
                              path_, header, header_));
    if (!started_) {  // the fix's first run: the grid starts here, with a row of the start state
      started_ = true;
      start_time_ = sim.time();
      write_row(sim);
    } else if (due(sim)) {
      // Continued from a restart written, in this step, before this fix's row: the straight
      // run wrote that row here, from this same state.
      write_row(sim);
    }
  }

  void end_of_step(Simulation& sim) override {
    if (due(sim)) write_row(sim);
  }

  void finish(Simulation&) override {
    if (file_ && std::fflush(file_) != 0) fail();
  }

  void save_state(ByteWriter& w) const override {
    w.put<std::uint8_t>(started_);
    w.put(start_time_);
    w.put(next_);
    w.put(last_step_);
    w.put(bytes_);
    w.put_string(path_);
    w.put_string(header_);
  }

  void restore_state(ByteReader& r) override {
    started_ = r.get<std::uint8_t>() != 0;
    start_time_ = r.get<double>();
    next_ = r.get<std::int64_t>();
    last_step_ = r.get<std::int64_t>();
    bytes_ = r.get<std::uint64_t>();
    saved_path_ = r.get_string();
    header_ = r.get_string();
    restored_ = true;
  }

 private:
  // Due when the time since the start reaches the next multiple of the interval (within a
  // relative 1e-9, as OutputSchedule: an interval that is a multiple of dt hits its steps).
  bool due(const Simulation& sim) const {
    return sim.step() != last_step_ &&
           sim.time() - start_time_ >= static_cast<double>(next_) * interval_ * (1 - 1e-9);
  }

  // The header; checks each compute (they may be added after this fix, so only now).
  std::string header_line(const Simulation& sim) {
    std::vector<std::string> ids;
    for (const auto& c : sim.computes()) ids.push_back(c->id());
    std::string header = "time";
    for (const auto& id : computes_) {
      const Compute* c = sim.find_compute(id);
      if (!c)
        throw Error(fmt::format("parameter 'computes': no compute '{}'{}; computes now: {}", id,
                                did_you_mean(id, ids), ids.empty() ? "none" : fmt::format("{}", fmt::join(ids, ", "))));
      if (c->per_particle())
        throw Error(fmt::format("parameter 'computes': compute '{}' ({}) gives one value per particle, not named "
                                "values",
                                id, c->style()));
      for (const auto& column : c->columns()) header += "," + column;
    }
    return header;
  }

  // Opens the file: a new one with its header, or, continuing a restart's run, the one that
  // run wrote, cut back to the length it had at the restart.
  void open(const std::string& header) {
    std::error_code ec;
    opened_ = true;
    const bool continuing = restored_ && saved_path_ == path_ && std::filesystem::exists(path_, ec);
    if (!comm::root()) {  // the other ranks of a distributed run keep the count of bytes only
      if (!continuing) {
        bytes_ = header.size() + 1;
        header_ = header;
      }
      return;
    }
    if (continuing) {
      const auto size = std::filesystem::file_size(path_, ec);
      if (!ec && size >= bytes_) std::filesystem::resize_file(path_, bytes_, ec);
      else
        spdlog::warn("sample '{}': '{}' is shorter than when the restart was written; appending to it", id(), path_);
      if (ec) throw Error(fmt::format("parameter 'file': cannot cut '{}' back to the restart: {}", path_, ec.message()));
      file_ = std::fopen(path_.c_str(), "ab");
    } else {
      file_ = std::fopen(path_.c_str(), "wb");
    }
    if (!file_) throw Error(fmt::format("parameter 'file': cannot write '{}': {}", path_, std::strerror(errno)));
    if (!continuing) {
      bytes_ = 0;
      header_ = header;
      write(header + "\n");
    }
  }

  void write_row(Simulation& sim) {
    std::string row = fmt::format("{}", sim.time());
    for (const auto& id : computes_) {
      std::vector<double> v;
      sim.find_compute(id)->evaluate(sim, v);
      for (double x : v) row += fmt::format(",{}", x);
    }
    write(row + "\n");
    last_step_ = sim.step();
    // The next multiple not yet reached (an interval shorter than a step skips some).
    while (!(sim.time() - start_time_ < static_cast<double>(next_) * interval_ * (1 - 1e-9))) ++next_;
  }

  // A row goes out whole or the run stops: a full disk must not leave a cut row behind a run
  // that says it succeeded.
  void write(const std::string& text) {
    if (!file_) {  // not rank 0
      bytes_ += text.size();
      return;
    }
    if (std::fwrite(text.data(), 1, text.size(), file_) != text.size() || std::fflush(file_) != 0) fail();
    bytes_ += text.size();
  }
  [[noreturn]] void fail() const {
    throw Error(fmt::format("cannot write '{}': {}", path_, std::strerror(errno)));
  }

  std::vector<std::string> computes_;
  double interval_;
  std::string path_, saved_path_, header_;
  std::FILE* file_ = nullptr;
  bool started_ = false, restored_ = false, opened_ = false;
  double start_time_ = 0;
  std::int64_t next_ = 1, last_step_ = -1;  // next multiple of the interval due; step of the last row
  std::uint64_t bytes_ = 0;                  // the file's length
};

}  // namespace

void register_sample(StyleRegistry& r) {
  r.add({"sample",
         StyleKind::fix,
         "computes' values (probes, gauges, ...) every `interval` seconds, as a CSV time series",
         {{"computes", ParamType::StringList, std::nullopt, "", "ids of the computes to sample (named values only)"},
          ParamSpec{"interval", ParamType::Real, std::nullopt, "s", "simulated time between rows"}.above(0),
          {"file", ParamType::String, std::nullopt, "", "the CSV file (directories are created)"}},
         [](const std::string& id, const Params& p) { return std::make_unique<Sample>(id, p); }, nullptr});
}

}  // namespace pbf
