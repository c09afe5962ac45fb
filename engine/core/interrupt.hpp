#pragma once
// Signals during a run. While an InterruptWatch exists, the first SIGINT (Ctrl-C) only sets a
// flag: the run loop finishes the step, writes a restart and stops cleanly. The handler then
// restores the default action, so a second Ctrl-C ends the process at once. A distributed run
// takes SIGTERM the same way. SIGUSR1 (what a batch system sends ahead of a time limit when
// asked, Slurm's --signal=USR1@SECONDS) asks for a restart after the step, and the run goes on.
#include <cstdint>
#include <string>

#include "engine/core/error.hpp"
#include "engine/core/run_view.hpp"

namespace pbf {

class InterruptWatch {
 public:
  InterruptWatch();
  ~InterruptWatch();
  InterruptWatch(const InterruptWatch&) = delete;
  InterruptWatch& operator=(const InterruptWatch&) = delete;
  // What the signals since the last call ask for. Collective in a distributed run (one
  // reduction): the ranks see a signal at slightly different times, and all act after the
  // same step, the first at which any of them saw it.
  // A live view's wishes (engine/core/run_view.hpp) are agreed in the same reduction.
  struct Requests {
    bool stop = false, restart = false;
    std::string reason;  // a stop's: "interrupted (Ctrl-C)", or what request_stop said
    ViewWishes view;     // the largest over the ranks: rank 0's
  };
  static Requests requested(const ViewWishes& view = {});
  // Asks, from inside a step (a Python callback that raised), for the stop Ctrl-C makes:
  // after the step, with a restart; the message starts with `reason`.
  static void request_stop(const std::string& reason);
};

// While one exists inside a run (a Python callback runs), SIGINT has the action it had before
// the run (Python's), so that Ctrl-C reaches the code running then; the run's comes back after.
class InterruptPause {
 public:
  InterruptPause();
  ~InterruptPause();
  InterruptPause(const InterruptPause&) = delete;
  InterruptPause& operator=(const InterruptPause&) = delete;
};

// A run stopped by Ctrl-C (or request_stop) after writing a restart; the command line exits
// with 130.
class Interrupted : public Error {
 public:
  Interrupted(const std::string& message, std::string restart) : Error(message), restart_(std::move(restart)) {}
  const std::string& restart() const { return restart_; }

 private:
  std::string restart_;
};

}  // namespace pbf
