#pragma once
// A request from outside a run to end it at the next step boundary: the command line sets it on
// Ctrl-C or a termination request, the Python module on KeyboardInterrupt, a study for the cases
// still running. The step loops poll it before each attempt; a run that stops there keeps every
// converged step, with status `interrupted` (RunFailure::Kind::interrupted).

#include <atomic>

namespace tsm::solver {

class StopRequest {
 public:
  /// Async-signal-safe: a lock-free atomic store, all a signal handler may do.
  void request() noexcept { requested_.store(true, std::memory_order_relaxed); }
  bool requested() const noexcept { return requested_.load(std::memory_order_relaxed); }

 private:
  static_assert(std::atomic<bool>::is_always_lock_free, "a signal handler may only touch a lock-free atomic");
  std::atomic<bool> requested_{false};
};

/// Whether `stop` (null: none) asks the run to end.
inline bool stop_requested(const StopRequest* stop) { return stop && stop->requested(); }

}  // namespace tsm::solver
