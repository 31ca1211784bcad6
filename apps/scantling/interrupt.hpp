#pragma once
/// @file
/// SIGINT and SIGTERM during a long command: the handler only sets a flag (about all a signal
/// handler may safely do), which the command polls so that it stops between steps and removes
/// its partial outputs instead of dying in the middle of a write.

#include <signal.h>

#include <array>
#include <string>

namespace scantling::app {

/// Installs the SIGINT and SIGTERM handlers for its lifetime and restores the previous ones
/// when destroyed. The handlers are one-shot: a second Ctrl-C gets the default action and ends
/// the process at once (a run that does not poll can still be stopped). A signal that is
/// ignored when the scope starts (background jobs of a shell) stays ignored. One scope at a
/// time.
class InterruptScope {
  public:
    InterruptScope();
    ~InterruptScope();

    InterruptScope(const InterruptScope&) = delete;
    InterruptScope& operator=(const InterruptScope&) = delete;

    /// True once SIGINT or SIGTERM was received.
    bool requested() const;
    /// The signal received (SIGINT, SIGTERM), 0 when none.
    int signal_number() const;

  private:
    std::array<struct sigaction, 2> previous_{};  // SIGINT, SIGTERM
};

/// Prints "scantling: error: <signal>: <message>" (one line, as main.cpp prints errors) and
/// exits with 128 + `signal_number` (130 for SIGINT, 143 for SIGTERM), the shells' convention
/// for a process stopped by a signal. Call after the partial outputs were removed.
[[noreturn]] void exit_interrupted(const std::string& message, int signal_number);

}  // namespace scantling::app
