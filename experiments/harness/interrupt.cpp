// SIGINT flag for suite runs (interrupt.h).
#include "experiments/harness/interrupt.h"

#include <csignal>

namespace dv {

namespace {

volatile std::sig_atomic_t g_interrupted = 0;
struct sigaction g_previous {};
bool g_installed = false;

extern "C" void on_sigint(int) {
  g_interrupted = 1;
}

}  // namespace

void install_interrupt_handler() {
  struct sigaction action {};
  action.sa_handler = on_sigint;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND;
  g_installed = sigaction(SIGINT, &action, &g_previous) == 0;
}

void restore_interrupt_handler() {
  if (g_installed) sigaction(SIGINT, &g_previous, nullptr);
  g_installed = false;
}

InterruptScope::InterruptScope() {
  clear_interrupt();
  install_interrupt_handler();
}
InterruptScope::~InterruptScope() {
  restore_interrupt_handler();
}

bool interrupt_requested() {
  return g_interrupted != 0;
}
void request_interrupt() {
  g_interrupted = 1;
}
void clear_interrupt() {
  g_interrupted = 0;
}

}  // namespace dv
