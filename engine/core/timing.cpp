#include "engine/core/timing.hpp"

#include <fmt/format.h>

namespace pbf {

std::size_t TimingTable::row(const std::string& stage, const std::string& label) {
  for (std::size_t r = 0; r < rows_.size(); ++r)
    if (rows_[r].stage == stage && rows_[r].label == label) return r;
  rows_.push_back({stage, label, 0.0});
  return rows_.size() - 1;
}

double TimingTable::seconds(const std::string& stage, const std::string& label) const {
  for (const auto& r : rows_)
    if (r.stage == stage && r.label == label) return r.seconds;
  return 0;
}

std::string TimingTable::format() const {
  const double total = wall_seconds > 0 ? wall_seconds : 1e-300;
  std::string out = fmt::format("Timing: {} step{} of {} particles in {:.3f} s\n", steps, steps == 1 ? "" : "s", particles,
                                wall_seconds);
  out += fmt::format("  {:<44} {:>10} {:>7}\n", "stage / fix", "seconds", "share");
  double accounted = 0;
  std::string stage;
  for (std::size_t r = 0; r < rows_.size(); ++r) {
    if (rows_[r].stage == stage) continue;
    stage = rows_[r].stage;
    double stage_seconds = 0;
    for (const auto& row : rows_)
      if (row.stage == stage) stage_seconds += row.seconds;
    accounted += stage_seconds;
    out += fmt::format("  {:<44} {:>10.3f} {:>6.1f}%\n", stage, stage_seconds, 100 * stage_seconds / total);
    for (const auto& row : rows_)
      if (row.stage == stage)
        out += fmt::format("    {:<42} {:>10.3f} {:>6.1f}%\n", row.label, row.seconds, 100 * row.seconds / total);
  }
  out += fmt::format("  {:<44} {:>10.3f} {:>6.1f}%\n", "other (loop, setup)", wall_seconds - accounted,
                     100 * (wall_seconds - accounted) / total);
  const double rate = wall_seconds > 0 ? static_cast<double>(steps) * static_cast<double>(particles) / wall_seconds : 0;
  out += fmt::format("  particle-steps per second: {:.4g}\n", rate);
  out += fmt::format("  neighbours per particle: mean {:.1f}, max {}", neighbor_mean, neighbor_max);
  if (ranks > 1) {
    out += fmt::format("\n  {} MPI ranks; particles per rank: min {:.0f}, mean {:.1f}, max {:.0f} (max/mean {:.3f}); "
                       "ghosts per rank: mean {:.0f}",
                       ranks, load_least, load_mean, load_most, load_mean > 0 ? load_most / load_mean : 0.0,
                       ghosts_mean);
    out += fmt::format("\n  communication on rank 0: {:.3f} s, {:.1f}% (migration, ghosts, and the ghosts' updates "
                       "inside the fixes' rows)",
                       communication_seconds, 100 * communication_seconds / total);
    out += fmt::format("\n  communication of any rank: least {:.3f} s, {:.1f}%, most {:.3f} s, {:.1f}% (beyond the least: "
                       "waiting for slower ranks)",
                       communication_least, 100 * communication_least / total, communication_most,
                       100 * communication_most / total);
  }
  return out;
}

}  // namespace pbf
