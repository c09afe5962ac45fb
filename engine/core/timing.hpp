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
  // A distributed run: ranks, particles per rank (least, mean, most), seconds communicating in all
  // (the communication rows, and the ghosts' updates inside the fixes' rows): rank 0's, and the
  // least and most of any rank. A rank's time includes waiting for slower ranks at each
  // exchange; the least is nearest the transfers' own cost (the last rank to arrive waits least).
  int ranks = 1;
  double ghosts_mean = 0;  // ghosts per rank, mean over ranks and neighbour builds
  double load_least = 0, load_mean = 0, load_most = 0, communication_seconds = 0, communication_least = 0,
         communication_most = 0;

  std::string format() const;

 private:
  std::vector<Row> rows_;
};

}  // namespace pbf
