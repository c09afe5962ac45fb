#pragma once
// Thermo output: every K steps one line of the columns a script asks for (step, time, dt,
// particles, and compute values "id" or "id.name", Compute::columns), logged under a header
// of names and one of units, and optionally written to CSV (a "# units: ..." comment line,
// then a header row of names).
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

namespace pbf {

class Simulation;

class Thermo {
 public:
  // Checks the columns against the computes defined now, then (re)opens the CSV file.
  void configure(const Simulation& sim, int every, std::vector<std::string> columns, const std::string& csv_path);
  int every() const { return every_; }
  const std::vector<std::string>& columns() const { return columns_; }

  // Every name thermo columns may use now; a column not in it is an error.
  static std::vector<std::string> valid_columns(const Simulation& sim);
  void check(const Simulation& sim) const { check(sim, columns_); }
  // The unit of each column ("-" for a count or a ratio), in order.
  std::vector<std::string> units(const Simulation& sim) const;

  void start_run(Simulation& sim);  // header lines; a line for the current step if due
  void end_of_step(Simulation& sim);
  // The values of the columns now.
  std::vector<double> values(Simulation& sim) const;
  // The lines output so far, and the last one's values (the live view follows them).
  std::int64_t lines_output() const { return lines_output_; }
  const std::vector<double>& last_line() const { return last_line_; }
  std::int64_t last_line_step() const { return last_step_; }

 private:
  static void check(const Simulation& sim, const std::vector<std::string>& columns);
  void output(Simulation& sim);
  // The comment line of units and the row of names that start a CSV (and each new set of columns).
  std::string csv_header(const Simulation& sim) const;
  bool keep_rows_before_restart(const Simulation& sim) const;
  void write_csv(const std::string& text);

  int every_ = 0;
  std::vector<std::string> columns_ = {"step", "time"};
  std::string csv_path_;
  std::ofstream csv_;
  std::int64_t last_step_ = -1;
  std::int64_t lines_output_ = 0;
  std::vector<double> last_line_;
};

}  // namespace pbf
