#include "engine/core/thermo.hpp"

#include "engine/distributed/comm.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <map>
#include <spdlog/spdlog.h>

#include "engine/core/error.hpp"
#include "engine/core/names.hpp"
#include "engine/core/simulation.hpp"

namespace pbf {

namespace {

// A column thermo can show: its name and unit, and the compute value it shows (none for the
// simulation's own step, time, dt and particles).
struct Column {
  std::string name, unit;
  Compute* compute = nullptr;
  std::size_t value = 0;
};

// Every column thermo can show now: the simulation's own, then each compute's named values.
std::vector<Column> available(const Simulation& sim) {
  std::vector<Column> out = {{"step", "-"}, {"time", "s"}, {"dt", "s"}, {"particles", "-"}};
  for (const auto& c : sim.computes()) {
    if (c->per_particle()) continue;
    const auto names = c->columns();
    const auto units = c->units();
    for (std::size_t k = 0; k < names.size(); ++k) out.push_back({names[k], units.at(k), c.get(), k});
  }
  return out;
}

const Column& find_column(const std::vector<Column>& columns, const std::string& name) {
  for (const auto& c : columns)
    if (c.name == name) return c;
  throw Error(fmt::format("thermo: column '{}' names no compute value", name));
}

// Columns at least 14 wide, and always a space before a long name.
std::size_t width(const std::string& column) { return std::max<std::size_t>(14, column.size() + 2); }

}  // namespace

void Thermo::configure(const Simulation& sim, int every, std::vector<std::string> columns,
                       const std::string& csv_path) {
  if (every < 0) throw Error(fmt::format("thermo: 'every' must be >= 0, got {}", every));
  if (columns.empty()) throw Error("thermo: 'columns' must name at least one column");
  check(sim, columns);
  every_ = every;
  const bool same_columns = columns == columns_;
  columns_ = std::move(columns);
  if (csv_path != csv_path_) {
    csv_.close();
    csv_path_ = csv_path;
    if (!csv_path_.empty() && comm::root()) {  // a distributed run's file is rank 0's
      const auto parent = std::filesystem::path(csv_path_).parent_path();
      std::error_code ec;
      if (!parent.empty()) std::filesystem::create_directories(parent, ec);
      const bool continued = keep_rows_before_restart(sim);
      csv_.open(csv_path_, continued ? std::ios::app : std::ios::trunc);
      if (!csv_) throw Error(fmt::format("thermo: cannot write CSV file '{}'", csv_path_));
      if (!continued) write_csv(csv_header(sim));
    }
  } else if (csv_.is_open() && !same_columns) {  // new columns: new header lines
    write_csv(csv_header(sim));
  }
}

std::vector<std::string> Thermo::valid_columns(const Simulation& sim) {
  std::vector<std::string> valid;
  for (const auto& c : available(sim)) valid.push_back(c.name);
  return valid;
}

void Thermo::check(const Simulation& sim, const std::vector<std::string>& columns) {
  const auto valid = valid_columns(sim);
  for (const auto& col : columns)
    if (std::find(valid.begin(), valid.end(), col) == valid.end())
      throw Error(fmt::format("thermo: unknown column '{}'{}; valid columns now: {}", col, did_you_mean(col, valid),
                              fmt::join(valid, ", ")));
}

std::vector<std::string> Thermo::units(const Simulation& sim) const {
  const auto all = available(sim);
  std::vector<std::string> out;
  for (const auto& col : columns_) out.push_back(find_column(all, col).unit);
  return out;
}

std::vector<double> Thermo::values(Simulation& sim) const {
  const auto all = available(sim);
  std::map<std::string, std::vector<double>> evaluated;  // each compute once per line
  std::vector<double> out;
  for (const auto& name : columns_) {
    const Column& col = find_column(all, name);
    if (name == "step") out.push_back(static_cast<double>(sim.step()));
    else if (name == "time") out.push_back(sim.time());
    else if (name == "dt") out.push_back(sim.timestep());
    else if (name == "particles") out.push_back(static_cast<double>(sim.global_count()));
    else {
      auto it = evaluated.find(col.compute->id());
      if (it == evaluated.end()) {
        std::vector<double> v;
        col.compute->evaluate(sim, v);
        it = evaluated.emplace(col.compute->id(), std::move(v)).first;
      }
      out.push_back(it->second.at(col.value));
    }
  }
  return out;
}

std::string Thermo::csv_header(const Simulation& sim) const {
  const auto u = units(sim);
  std::string line = "# units:";
  for (std::size_t k = 0; k < columns_.size(); ++k) line += fmt::format("{} {} {}", k ? "," : "", columns_[k], u[k]);
  return fmt::format("{}\n{}\n", line, fmt::join(columns_, ","));
}

// A run continued from a restart, writing the CSV its first run wrote with the same
// columns, keeps that file's rows of the steps before the restart's and writes the rest
// again: the file reads as one run's (the same bytes as the run that never stopped). Any
// other CSV starts afresh.
bool Thermo::keep_rows_before_restart(const Simulation& sim) const {
  const RestartNote& restart = sim.last_restart();
  if (!restart.read || restart.step != sim.step() || columns_.front() != "step") return false;
  std::ifstream in(csv_path_, std::ios::binary);
  const std::string header = csv_header(sim);
  std::string text(header.size(), '\0');
  if (!in.read(text.data(), static_cast<std::streamsize>(text.size())) || text != header) return false;
  std::uintmax_t keep = header.size();
  for (std::string row; std::getline(in, row) && !in.eof();) {  // whole rows only
    const std::string step = row.substr(0, row.find(','));
    if (step.empty() || step.find_first_not_of("0123456789") != std::string::npos || std::stoll(step) >= sim.step())
      break;  // a later step, or new header lines
    keep += row.size() + 1;
  }
  std::error_code ec;
  std::filesystem::resize_file(csv_path_, keep, ec);
  return !ec;
}

// A line goes out whole or the run stops: a full disk must not leave a CSV cut mid-line
// behind a run that says it succeeded.
void Thermo::write_csv(const std::string& text) {
  csv_ << text;
  csv_.flush();
  if (!csv_) throw Error(fmt::format("thermo: cannot write CSV file '{}' (disk full?)", csv_path_));
}

void Thermo::start_run(Simulation& sim) {
  if (every_ <= 0) return;
  check(sim);
  // The names, and under each its unit in brackets.
  const auto u = units(sim);
  std::string names, units_line;
  for (std::size_t k = 0; k < columns_.size(); ++k) {
    names += fmt::format("{:>{}}", columns_[k], width(columns_[k]));
    units_line += fmt::format("{:>{}}", "[" + u[k] + "]", width(columns_[k]));
  }
  spdlog::info("{}", names);
  spdlog::info("{}", units_line);
  if (csv_.is_open()) sim.outputs().wrote("thermo CSV", csv_path_);
  if (sim.step() % every_ == 0) output(sim);
}

void Thermo::end_of_step(Simulation& sim) {
  if (every_ > 0 && sim.step() % every_ == 0) output(sim);
}

void Thermo::output(Simulation& sim) {
  if (sim.step() == last_step_) return;  // never twice for one step
  last_step_ = sim.step();
  const auto v = values(sim);
  // (With no particles, what measures them is NaN: nothing to measure, no overflow.)
  for (std::size_t k = 0; k < v.size() && sim.global_count() > 0; ++k)
    if (!std::isfinite(v[k]))  // an overflow the finite-position check cannot see (v^2 in the energy)
      throw Error(fmt::format("step {}: thermo column '{}' is {}: the state has overflowed", sim.step(), columns_[k],
                              v[k]));
  last_line_ = v;
  ++lines_output_;
  std::string line;
  for (std::size_t k = 0; k < v.size(); ++k) line += fmt::format("{:>{}.7g}", v[k], width(columns_[k]));
  spdlog::info("{}", line);
  if (csv_.is_open()) {
    std::string row;
    for (std::size_t k = 0; k < v.size(); ++k) row += fmt::format("{}{}", k ? "," : "", v[k]);
    write_csv(row + '\n');
  }
}

}  // namespace pbf
