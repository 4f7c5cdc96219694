#pragma once
// Ctrl-C and `kill` (SIGINT, SIGTERM) without half-written outputs.
//
// Outside of output work an interrupt ends the process at once (exit 128 + signal): nothing of
// ours is open then. While a DeferInterrupts is alive (a file being replaced, a staging folder, a
// recording) the signal only sets a flag; the work checks it at safe points with
// throw_if_interrupted() and unwinds, so staging folders are removed and recordings are marked
// incomplete. A second signal ends the process regardless.
#include <stdexcept>

namespace makeway::io {

/// Thrown at a safe point after SIGINT/SIGTERM. exit_code() is 128 + the signal.
class Interrupted : public std::runtime_error {
  public:
    explicit Interrupted(int signal_number);
    int exit_code() const { return 128 + signal_; }

  private:
    int signal_;
};

/// Installs the SIGINT/SIGTERM handlers (once, from main).
void install_interrupt_handlers();

/// True once a signal arrived (and was deferred).
bool interrupt_requested();

/// Throws Interrupted when a signal arrived.
void throw_if_interrupted();

/// While alive, signals are deferred (nestable, any thread).
class DeferInterrupts {
  public:
    DeferInterrupts();
    ~DeferInterrupts();
    DeferInterrupts(const DeferInterrupts&) = delete;
    DeferInterrupts& operator=(const DeferInterrupts&) = delete;
};

/// For tests: forget a deferred signal.
void clear_interrupt_for_testing();

}  // namespace makeway::io
