// restart: writes a restart file every K steps or every T simulated seconds, PATH with '*'
// replaced by the step, keeping the newest `keep` files. Each file is written under a
// temporary name and renamed when complete, so the newest one on disk is always whole.
// On Ctrl-C the run loop asks this fix for a restart of the current step.
#include <algorithm>
#include <filesystem>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "engine/core/error.hpp"
#include "engine/registry/builtin_styles.hpp"
#include "engine/io/bytes.hpp"
#include "engine/output/path_pattern.hpp"
#include "engine/io/restart.hpp"
#include "engine/output/output_schedule.hpp"
#include "engine/core/simulation.hpp"
#include "engine/distributed/comm.hpp"

namespace pbf {

namespace {

class PeriodicRestart : public Fix {
 public:
  PeriodicRestart(const std::string& id, const Params& p)
      : Fix(id, "restart"), path_(p.string("path"), "the step number"), keep_(p.integer("keep")), schedule_(p, false) {
  }

  std::vector<Stage> stages() const override { return {Stage::end_of_step}; }
  Role role() const override { return Role::output; }
  bool runs_distributed() const override { return true; }  // every rank writes its part of one file

  void init(Simulation& sim) override {
    path_.create_directory();
    schedule_.start(sim);
    if (!checked_ && written_.empty() && comm::root()) warn_about_later_restarts(sim);
    checked_ = true;
  }

  void end_of_step(Simulation& sim) override {
    if (schedule_.due(sim)) {
      schedule_.done(sim);  // the state saved in the file counts this restart, as the run goes on after it
      write(sim);
    }
  }

  // Ctrl-C or SIGUSR1: one more file, outside the schedule, so the periodic ones stay where
  // they were.
  std::optional<std::string> write_restart_now(Simulation& sim) override {
    if (written_.empty() || written_.back().first != sim.step()) write(sim);
    return written_.back().second;
  }

  void save_state(ByteWriter& w) const override {
    schedule_.save(w);
    w.put<std::uint64_t>(written_.size());
    for (const auto& [step, path] : written_) {
      w.put(step);
      w.put_string(path);
    }
  }

  void restore_state(ByteReader& r) override {
    schedule_.restore(r);
    const auto count = r.get<std::uint64_t>();
    r.require(count, 2 * sizeof(std::uint64_t));
    written_.resize(count);
    for (auto& [step, path] : written_) {
      step = r.get<std::int64_t>();
      path = r.get_string();
    }
  }

 private:
  // Restarts of a later step where this run writes its own: most often those of a run this
  // one was meant to continue. Starting again writes over that run's frames: said loudly.
  void warn_about_later_restarts(const Simulation& sim) const {
    const std::string& pattern = path_.pattern();
    const std::filesystem::path folder = std::filesystem::path(pattern).parent_path();
    const std::string name = std::filesystem::path(pattern).filename().string();
    const std::size_t star = name.find('*');
    if (star == std::string::npos) return;  // the '*' is in the folder's name
    const std::string prefix = name.substr(0, star), suffix = name.substr(star + 1);
    std::int64_t newest = -1;
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(folder.empty() ? "." : folder, ec)) {
      const std::string file = entry.path().filename().string();
      if (file.size() <= prefix.size() + suffix.size() || file.rfind(prefix, 0) != 0 ||
          file.compare(file.size() - suffix.size(), suffix.size(), suffix) != 0)
        continue;
      const std::string digits = file.substr(prefix.size(), file.size() - prefix.size() - suffix.size());
      if (digits.size() > 18 || digits.find_first_not_of("0123456789") != std::string::npos) continue;
      newest = std::max<std::int64_t>(newest, std::stoll(digits));
    }
    if (newest <= sim.step()) return;
    const std::string file = path_.with(std::to_string(newest));
    spdlog::warn("fix '{}' (restart): '{}' is the restart of a run that reached step {}; this run starts at step {} "
                 "and writes over that run's outputs (to continue it instead, run the script with -v restart={} "
                 "and build the scene with pbf.scene)",
                 id(), file, newest, sim.step(), file);
  }

  void write(Simulation& sim) {
    const std::string path = path_.with(std::to_string(sim.step()));
    written_.emplace_back(sim.step(), path);
    write_restart(sim, path);
    // Only now that the new file is complete, the oldest go.
    while (written_.size() > static_cast<std::size_t>(keep_)) {
      std::error_code ec;
      if (written_.front().second != path && comm::root()) {
        std::filesystem::remove(written_.front().second, ec);
        sim.outputs().removed("restarts");
      }
      written_.erase(written_.begin());
    }
  }

  PathPattern path_;
  std::int64_t keep_;
  OutputSchedule schedule_;
  std::vector<std::pair<std::int64_t, std::string>> written_;  // (step, path), oldest first
  bool checked_ = false;                                        // for an earlier run's restarts
};

}  // namespace

void register_restart(StyleRegistry& r) {
  auto params = OutputSchedule::params("restarts");
  params.insert(params.begin(),
                {{"path", ParamType::String, std::string("run.*.restart"), "",
                  "file name pattern; '*' becomes the step number (directories are created)"},
                 ParamSpec{"keep", ParamType::Integer, std::int64_t{2}, "", "how many of the newest restarts to keep"}
                     .within(1, 1000000)});
  r.add({"restart", StyleKind::fix, "writes restart files periodically (and on Ctrl-C or SIGUSR1), keeping the newest",
         std::move(params), [](const std::string& id, const Params& p) { return std::make_unique<PeriodicRestart>(id, p); },
         nullptr});
}

}  // namespace pbf
