#include "engine/core/interrupt.hpp"

#include <algorithm>
#include <csignal>
#include <span>
#include <unistd.h>

#include "engine/distributed/comm.hpp"

namespace pbf {

namespace {

volatile std::sig_atomic_t interrupt_flag = 0, restart_flag = 0;
std::string stop_reason;  // request_stop's, else Ctrl-C's
struct sigaction previous_interrupt, previous_terminate, previous_user1, paused_interrupt;
bool watching = false;

// A rank told to stop while it waits for a rank that died (mpirun sends SIGTERM to the others
// when one crashes) would never reach the end of its step: it ends this long after the signal
// unless it stopped cleanly first.
constexpr unsigned kGraceSeconds = 30;

extern "C" void on_interrupt(int signal) {
  interrupt_flag = 1;
  std::signal(signal, SIG_DFL);  // a second one is not caught
  if (signal == SIGTERM) alarm(kGraceSeconds);  // SIGALRM's default action ends the process
}

extern "C" void on_restart_request(int) { restart_flag = 1; }

}  // namespace

InterruptWatch::InterruptWatch() {
  interrupt_flag = 0;
  stop_reason.clear();
  struct sigaction action = {};
  action.sa_handler = on_interrupt;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, &previous_interrupt);
  // mpirun forwards SIGTERM to every rank (and turns Ctrl-C into it), as a batch system's
  // time limit does: a distributed run takes it as Ctrl-C.
  if (comm::distributed()) sigaction(SIGTERM, &action, &previous_terminate);
  restart_flag = 0;
  action.sa_handler = on_restart_request;
  sigaction(SIGUSR1, &action, &previous_user1);
  watching = true;
}

InterruptWatch::~InterruptWatch() {
  watching = false;
  alarm(0);
  sigaction(SIGINT, &previous_interrupt, nullptr);
  if (comm::distributed()) sigaction(SIGTERM, &previous_terminate, nullptr);
  sigaction(SIGUSR1, &previous_user1, nullptr);
}

InterruptWatch::Requests InterruptWatch::requested(const ViewWishes& view) {
  double seen[2 + ViewWishes::kCount] = {interrupt_flag != 0 ? 1.0 : 0.0, restart_flag != 0 ? 1.0 : 0.0};
  if (seen[1] > 0) restart_flag = 0;  // one restart a signal (one arriving now waits for the next step)
  ViewWishes wished = view;
  std::copy(wished.data(), wished.data() + ViewWishes::kCount, seen + 2);
  comm::max(std::span<double>(seen));
  Requests r{seen[0] > 0, seen[1] > 0, stop_reason, {}};
  std::copy(seen + 2, seen + 2 + ViewWishes::kCount, r.view.data());
  if (r.stop && r.reason.empty())
    r.reason = interrupt_flag != 0 || !comm::distributed() ? "interrupted (Ctrl-C)" : "stopped by another rank";
  return r;
}

InterruptPause::InterruptPause() {
  if (watching) sigaction(SIGINT, &previous_interrupt, &paused_interrupt);
}

InterruptPause::~InterruptPause() {
  if (watching) sigaction(SIGINT, &paused_interrupt, nullptr);
}

void InterruptWatch::request_stop(const std::string& reason) {
  if (stop_reason.empty()) stop_reason = reason;
  interrupt_flag = 1;
}

}  // namespace pbf
