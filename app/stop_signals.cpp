#include "stop_signals.hpp"

#include <signal.h>
#include <time.h>

#include <atomic>

namespace tsm::app {
namespace {

// The same request often comes twice: timeout(1) signals the program and then its process group,
// a batch system each process of the job. A second signal within this many nanoseconds of the
// first is that one again; a later one ends the program.
constexpr long long same_request_ns = 1'000'000'000;

solver::StopRequest stop;
std::atomic<int> stopped_by{0};
std::atomic<long long> first_signal_ns{0};

long long now_ns() {
  timespec t{};
  ::clock_gettime(CLOCK_MONOTONIC, &t);  // async-signal-safe
  return static_cast<long long>(t.tv_sec) * 1'000'000'000 + t.tv_nsec;
}

extern "C" void on_stop_signal(int signal) {
  const long long now = now_ns();
  if (!stop.requested()) {
    first_signal_ns.store(now, std::memory_order_relaxed);
    stopped_by.store(signal, std::memory_order_relaxed);
    stop.request();
    return;
  }
  if (now - first_signal_ns.load(std::memory_order_relaxed) < same_request_ns) return;
  struct sigaction fallback = {};  // the second request: end now, as the signal does by default
  fallback.sa_handler = SIG_DFL;
  ::sigaction(signal, &fallback, nullptr);
  ::raise(signal);
}

}  // namespace

const solver::StopRequest& install_stop_signals() {
  static_assert(std::atomic<int>::is_always_lock_free && std::atomic<long long>::is_always_lock_free);
  struct sigaction handler = {};
  handler.sa_handler = on_stop_signal;
  sigemptyset(&handler.sa_mask);
  sigaddset(&handler.sa_mask, SIGINT);  // one handler at a time
  sigaddset(&handler.sa_mask, SIGTERM);
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
