#include "scantling/interrupt.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <cstdlib>

#include <scantling/core/text_escape.hpp>

namespace scantling::app {
namespace {

constexpr std::array<int, 2> kSignals = {SIGINT, SIGTERM};  // the order of previous_
constexpr int kExitBySignalBase = 128;

// A signal handler can reach nothing but static storage: this flag is the one global of the
// app, written only by the handler and read by the InterruptScope that installed it.
volatile std::sig_atomic_t received_signal = 0;

void on_signal(int signal_number) { received_signal = signal_number; }

const char* signal_name(int signal_number) {
    return signal_number == SIGINT ? "SIGINT" : signal_number == SIGTERM ? "SIGTERM" : "signal";
}

}  // namespace

InterruptScope::InterruptScope() {
    received_signal = 0;
    struct sigaction action {};
    action.sa_handler = on_signal;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESETHAND | SA_RESTART;  // one-shot; reads and writes carry on
    for (std::size_t i = 0; i < kSignals.size(); ++i) {
        sigaction(kSignals[i], nullptr, &previous_[i]);
        // An ignored signal stays ignored: a shell starts background jobs with SIGINT ignored,
        // and a Ctrl-C meant for the foreground must not stop them.
        if (previous_[i].sa_handler != SIG_IGN) sigaction(kSignals[i], &action, nullptr);
    }
}

InterruptScope::~InterruptScope() {
    for (std::size_t i = 0; i < kSignals.size(); ++i) {
        sigaction(kSignals[i], &previous_[i], nullptr);
    }
}

bool InterruptScope::requested() const { return received_signal != 0; }

int InterruptScope::signal_number() const { return received_signal; }

void exit_interrupted(const std::string& message, int signal_number) {
    std::string line = message;
    std::replace(line.begin(), line.end(), '\n', ' ');
    fmt::print(stderr, "scantling: error: {}: {}\n", signal_name(signal_number),
               escape_control_characters(line));  // as main.cpp: the path may hold any byte
    std::fflush(stderr);
    std::exit(kExitBySignalBase + signal_number);
}

}  // namespace scantling::app
