#include "io/interrupt.hpp"

#include <unistd.h>

#include <atomic>
#include <csignal>
#include <string>

namespace makeway::io {
namespace {

std::atomic<int> g_deferring{0};
std::atomic<int> g_signal{0};

void write_stderr(const char* text) {
    std::size_t n = 0;
    while (text[n] != '\0') ++n;
    [[maybe_unused]] const ssize_t w = ::write(STDERR_FILENO, text, n);
}

extern "C" void on_signal(int sig) {
    // Only async-signal-safe calls here: atomics, write(2), _exit(2).
    if (g_deferring.load() == 0 || g_signal.load() != 0) {
        write_stderr("\nmakeway: interrupted\n");
        ::_exit(128 + sig);
    }
    g_signal.store(sig);
    write_stderr("\nmakeway: interrupted, stopping cleanly (again to quit at once)\n");
}

}  // namespace

Interrupted::Interrupted(int signal_number)
    : std::runtime_error(std::string("interrupted by ") +
                         (signal_number == SIGTERM ? "SIGTERM" : "SIGINT")),
      signal_(signal_number) {}

void install_interrupt_handlers() {
    struct sigaction sa {};
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESTART;
    sigaction(SIGINT, &sa, nullptr);
    sigaction(SIGTERM, &sa, nullptr);
}

bool interrupt_requested() { return g_signal.load() != 0; }

void throw_if_interrupted() {
    if (const int sig = g_signal.load()) throw Interrupted(sig);
}

DeferInterrupts::DeferInterrupts() { g_deferring.fetch_add(1); }
DeferInterrupts::~DeferInterrupts() { g_deferring.fetch_sub(1); }

void clear_interrupt_for_testing() { g_signal.store(0); }

}  // namespace makeway::io
