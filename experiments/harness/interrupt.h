// Ctrl-C for suite runs: a SIGINT handler that only sets a flag (the runner checks it between
// experiments, writes every finished row and a report of what was done, and exits 130). The
// handler resets itself, so a second Ctrl-C stops the process at once.
#pragma once

namespace dv {

void install_interrupt_handler();
void restore_interrupt_handler();

// Installs the handler (clearing the flag) for its lifetime.
class InterruptScope {
 public:
  InterruptScope();
  ~InterruptScope();
  InterruptScope(const InterruptScope&) = delete;
  InterruptScope& operator=(const InterruptScope&) = delete;
};
bool interrupt_requested();
// What the handler does; tests and drivers may call it directly.
void request_interrupt();
void clear_interrupt();

}  // namespace dv
