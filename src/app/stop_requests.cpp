#include "app/stop_requests.hpp"

#include <atomic>
#include <csignal>

#include <unistd.h>

namespace mimic::app {

namespace {

std::atomic<int> g_stops{0};

extern "C" void request_stop(int) {
  if (g_stops.fetch_add(1) == 0) return;
  static const char message[] = "\nsecond stop request: exiting at once; the last checkpoint on disk is kept\n";
  (void)!::write(STDERR_FILENO, message, sizeof message - 1);
  ::_exit(130);
}

}  // namespace

void handle_stop_signals() {
  std::signal(SIGINT, request_stop);
  std::signal(SIGTERM, request_stop);
}

int stop_requests() { return g_stops.load(); }

}  // namespace mimic::app
