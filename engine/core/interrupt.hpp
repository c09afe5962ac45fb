#pragma once
// Ctrl-C during a run. While an InterruptWatch exists, the first SIGINT only sets a flag:
// the run loop finishes the step, writes a restart and stops cleanly. The handler then
// restores the default action, so a second Ctrl-C ends the process at once. A distributed run
// takes SIGTERM the same way, and requested() is then collective.
#include <cstdint>
#include <string>

#include "engine/core/error.hpp"

namespace pbf {

class InterruptWatch {
 public:
  InterruptWatch();
  ~InterruptWatch();
  InterruptWatch(const InterruptWatch&) = delete;
  InterruptWatch& operator=(const InterruptWatch&) = delete;
  static bool requested();
};

// A run stopped by Ctrl-C after writing a restart; the command line exits with 130.
class Interrupted : public Error {
 public:
  Interrupted(const std::string& message, std::string restart) : Error(message), restart_(std::move(restart)) {}
  const std::string& restart() const { return restart_; }

 private:
  std::string restart_;
};

}  // namespace pbf
