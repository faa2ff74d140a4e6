#include "signals.hpp"

#include <unistd.h>

#include <csignal>

#include "command.hpp"

namespace fricon::app {

std::atomic<bool> stop_requested{false};
std::atomic<bool> has_iterate{false};
static_assert(std::atomic<bool>::is_always_lock_free, "the signal handler needs a lock-free flag");

namespace {

extern "C" void on_signal(int sig) {
  if (!has_iterate.load()) {
    // Only async-signal-safe calls here: write(2) and _exit(2).
    constexpr char kMessage[] = "fricon: interrupted (no iterate to write yet)\n";
    [[maybe_unused]] const ssize_t n = write(STDERR_FILENO, kMessage, sizeof kMessage - 1);
    _exit(kNotConverged);
  }
  if (stop_requested.exchange(true)) {
    std::signal(sig, SIG_DFL);
    std::raise(sig);
  }
}

}  // namespace

void install_signal_handlers() {
  struct sigaction action {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  sigaction(SIGUSR1, &action, nullptr);
}

}  // namespace fricon::app
