#include "app/stop_requests.hpp"

#include <atomic>
#include <csignal>

#include <unistd.h>

namespace mimic::app {

namespace {

std::atomic<int> g_stops{0};
std::atomic<int> g_first_signal{0};

extern "C" void request_stop(int signal) {
  if (g_stops.fetch_add(1) == 0) {
    g_first_signal.store(signal);
    return;
  }
  static const char message[] = "\nsecond stop request: exiting at once; the last checkpoint on disk is kept\n";
  (void)!::write(STDERR_FILENO, message, sizeof message - 1);
  ::_exit(130);
}

}  // namespace

void handle_stop_signals() {
  std::signal(SIGINT, request_stop);
  std::signal(SIGTERM, request_stop);
}

void release_stop_signals() {
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  g_stops.store(0);
  g_first_signal.store(0);
}

int stop_requests() { return g_stops.load(); }

int stop_signal() { return g_first_signal.load(); }

}  // namespace mimic::app
