#include "engine/core/interrupt.hpp"

#include <csignal>
#include <unistd.h>

#include "engine/distributed/comm.hpp"

namespace pbf {

namespace {

volatile std::sig_atomic_t interrupt_flag = 0;
struct sigaction previous_interrupt, previous_terminate;

// A rank told to stop while it waits for a rank that died (mpirun sends SIGTERM to the others
// when one crashes) would never reach the end of its step: it ends this long after the signal
// unless it stopped cleanly first.
constexpr unsigned kGraceSeconds = 30;

extern "C" void on_interrupt(int signal) {
  interrupt_flag = 1;
  std::signal(signal, SIG_DFL);  // a second one is not caught
  if (signal == SIGTERM) alarm(kGraceSeconds);  // SIGALRM's default action ends the process
}

}  // namespace

InterruptWatch::InterruptWatch() {
  interrupt_flag = 0;
  struct sigaction action = {};
  action.sa_handler = on_interrupt;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, &previous_interrupt);
  // mpirun forwards SIGTERM to every rank (and turns Ctrl-C into it), as a batch system's
  // time limit does: a distributed run takes it as Ctrl-C.
  if (comm::distributed()) sigaction(SIGTERM, &action, &previous_terminate);
}

InterruptWatch::~InterruptWatch() {
  alarm(0);
  sigaction(SIGINT, &previous_interrupt, nullptr);
  if (comm::distributed()) sigaction(SIGTERM, &previous_terminate, nullptr);
}

// The ranks see a signal at slightly different times: they stop after the same step, the
// first at which any of them saw it.
bool InterruptWatch::requested() {
  if (!comm::distributed()) return interrupt_flag != 0;
  return comm::max(interrupt_flag != 0 ? 1.0 : 0.0) > 0;
}

}  // namespace pbf
