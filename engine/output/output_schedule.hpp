#pragma once
// When a periodic output (a dump frame, a restart) is due: every K steps, or each time the
// simulated time since the output started reaches the next multiple of an interval (within
// a relative 1e-9, so an interval that is a multiple of dt hits its steps exactly); never
// twice in one step. Its counters are fix state: restarts carry them on.
#include <cstdint>
#include <string>
#include <vector>

#include "engine/registry/params.hpp"

namespace pbf {

class Simulation;
class ByteWriter;
class ByteReader;

class OutputSchedule {
 public:
  // The 'interval' and 'every' parameters of a style's schema (give exactly one).
  static std::vector<ParamSpec> params(const char* what);
  // `at_start`: the first output is due when the schedule starts (dump frame 0); otherwise
  // one interval later (a restart of the initial state would be useless).
  OutputSchedule(const Params& p, bool at_start);

  // Called in the fix's init: the first start fixes the time origin of the intervals. With an
  // `owner` (the fix, for the message) it warns when the first output after the start falls
  // beyond the end of the run: a frame interval longer than the run is most likely a slip of
  // the unit. (Restarts pass none: they are insurance, and a short run needs none.)
  void start(const Simulation& sim, const std::string& owner = "");
  bool due(const Simulation& sim) const;
  void done(const Simulation& sim);  // an output was written at this step
  // Outputs written so far (the next dump frame's number).
  std::int64_t count() const { return count_; }

  void save(ByteWriter& w) const;
  void restore(ByteReader& r);

 private:
  double interval_;
  std::int64_t every_;
  bool at_start_;
  bool started_ = false;
  double start_time_ = 0;
  std::int64_t start_step_ = 0, count_ = 0, last_step_ = -1;
};

}  // namespace pbf
