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
const std::vector<std::string> kBuiltinColumns = {"step", "time", "dt", "particles"};
// Columns at least 14 wide, and always a space before a long name.
std::size_t width(const std::string& column) { return std::max<std::size_t>(14, column.size() + 2); }
}

void Thermo::configure(int every, std::vector<std::string> columns, const std::string& csv_path) {
  if (every < 0) throw Error(fmt::format("thermo: 'every' must be >= 0, got {}", every));
  if (columns.empty()) throw Error("thermo: 'columns' must name at least one column");
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
      csv_.open(csv_path_);
      if (!csv_) throw Error(fmt::format("thermo: cannot write CSV file '{}'", csv_path_));
      write_csv(fmt::format("{}\n", fmt::join(columns_, ",")));
    }
  } else if (csv_.is_open() && !same_columns) {  // new columns: a new header row
    write_csv(fmt::format("{}\n", fmt::join(columns_, ",")));
  }
}

std::vector<std::string> Thermo::valid_columns(const Simulation& sim) {
  std::vector<std::string> valid = kBuiltinColumns;
  for (const auto& c : sim.computes()) {
    if (c->per_particle()) continue;
    const auto names = c->names();
    if (names.size() == 1) valid.push_back(c->id());
    else
      for (const auto& n : names) valid.push_back(c->id() + "." + n);
  }
  return valid;
}

void Thermo::check(const Simulation& sim) const {
  const auto valid = valid_columns(sim);
  for (const auto& col : columns_)
    if (std::find(valid.begin(), valid.end(), col) == valid.end())
      throw Error(fmt::format("thermo: unknown column '{}'{}; valid columns now: {}", col, did_you_mean(col, valid),
                              fmt::join(valid, ", ")));
}

std::vector<double> Thermo::values(Simulation& sim) const {
  std::map<std::string, std::vector<double>> evaluated;  // each compute once per line
  std::vector<double> out;
  for (const auto& col : columns_) {
    if (col == "step") out.push_back(static_cast<double>(sim.step()));
    else if (col == "time") out.push_back(sim.time());
    else if (col == "dt") out.push_back(sim.timestep());
    else if (col == "particles") out.push_back(static_cast<double>(sim.global_count()));
    else {
      const auto dot = col.find('.');
      const std::string id = col.substr(0, dot);
      Compute* compute = sim.find_compute(id);
      if (!compute) throw Error(fmt::format("thermo: column '{}' names no compute", col));
      auto it = evaluated.find(id);
      if (it == evaluated.end()) {
        std::vector<double> v;
        compute->evaluate(sim, v);
        it = evaluated.emplace(id, std::move(v)).first;
      }
      const auto names = compute->names();
      std::size_t k = 0;
      if (dot != std::string::npos)
        k = static_cast<std::size_t>(std::find(names.begin(), names.end(), col.substr(dot + 1)) - names.begin());
      out.push_back(it->second.at(k));
    }
  }
  return out;
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
  std::string header;
  for (const auto& c : columns_) header += fmt::format("{:>{}}", c, width(c));
  spdlog::info("{}", header);
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
  for (std::size_t k = 0; k < v.size(); ++k)
    if (!std::isfinite(v[k]))  // an overflow the finite-position check cannot see (v^2 in the energy)
      throw Error(fmt::format("step {}: thermo column '{}' is {}: the state has overflowed", sim.step(), columns_[k],
                              v[k]));
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
