#include "stop_signals.hpp"

#include <signal.h>

#include <atomic>

namespace tsm::app {
namespace {

solver::StopRequest stop;
std::atomic<int> stopped_by{0};

extern "C" void on_stop_signal(int signal) {
  stopped_by.store(signal, std::memory_order_relaxed);
  stop.request();
  // The second signal ends the program (sigaction is async-signal-safe).
  struct sigaction fallback = {};
  fallback.sa_handler = SIG_DFL;
  ::sigaction(SIGINT, &fallback, nullptr);
  ::sigaction(SIGTERM, &fallback, nullptr);
}

}  // namespace

const solver::StopRequest& install_stop_signals() {
  static_assert(std::atomic<int>::is_always_lock_free);
  struct sigaction handler = {};
  handler.sa_handler = on_stop_signal;
  sigemptyset(&handler.sa_mask);
  handler.sa_flags = SA_RESTART;
  ::sigaction(SIGINT, &handler, nullptr);
  ::sigaction(SIGTERM, &handler, nullptr);
  struct sigaction ignore = {};
  ignore.sa_handler = SIG_IGN;
  ::sigaction(SIGXFSZ, &ignore, nullptr);
  return stop;
}

const char* stop_signal_name() {
  switch (stopped_by.load(std::memory_order_relaxed)) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    default: return nullptr;
  }
}

}  // namespace tsm::app
