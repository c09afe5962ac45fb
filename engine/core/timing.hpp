#pragma once
// Wall time per stage and per fix, accumulated by the run loop and printed after a run.
#include <cstddef>
#include <string>
#include <vector>

namespace pbf {

class TimingTable {
 public:
  struct Row {
    std::string stage, label;
    double seconds = 0;
  };
  void clear() { rows_.clear(); }
  // Index of the row (stage, label), created on first use.
  std::size_t row(const std::string& stage, const std::string& label);
  void add(std::size_t row, double seconds) { rows_[row].seconds += seconds; }
  const std::vector<Row>& rows() const { return rows_; }
  double seconds(const std::string& stage, const std::string& label) const;

  // Per-run facts printed under the table.
  double wall_seconds = 0;
  long long steps = 0;
  std::size_t particles = 0;
  double neighbor_mean = 0;
  unsigned neighbor_max = 0;

  std::string format() const;

 private:
  std::vector<Row> rows_;
};

}  // namespace pbf
