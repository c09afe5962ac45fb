#include "engine/core/interrupt.hpp"

#include <csignal>

namespace pbf {

namespace {

volatile std::sig_atomic_t interrupt_flag = 0;
struct sigaction previous_action;

extern "C" void on_interrupt(int) {
  interrupt_flag = 1;
  std::signal(SIGINT, SIG_DFL);  // a second Ctrl-C is not caught
}

}  // namespace

InterruptWatch::InterruptWatch() {
  interrupt_flag = 0;
  struct sigaction action = {};
  action.sa_handler = on_interrupt;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, &previous_action);
}

InterruptWatch::~InterruptWatch() { sigaction(SIGINT, &previous_action, nullptr); }

bool InterruptWatch::requested() { return interrupt_flag != 0; }

}  // namespace pbf
