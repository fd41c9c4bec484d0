#include "src/interruptible.hpp"

#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>

namespace tsm::python {

namespace {

/// The signals, then `poll`, with the GIL held: whether either raised (the error stays set).
bool check(const std::function<void()>& poll) {
  py::gil_scoped_acquire acquire;
  if (PyErr_CheckSignals() != 0) return true;  // the main thread only
  if (!poll) return false;
  try {
    poll();
  } catch (py::error_already_set& e) {
    e.restore();
    return true;
  }
  return false;
}

}  // namespace

void run_interruptible(const std::function<void(const solver::StopRequest*)>& work, const std::function<void()>& poll) {
  solver::StopRequest stop;
  std::exception_ptr failure;
  bool done = false, interrupted = false;
  std::mutex mutex;
  std::condition_variable finished;
  {
    py::gil_scoped_release release;
    std::thread worker([&] {
      try {
        work(&stop);
      } catch (...) {
        failure = std::current_exception();
      }
      std::lock_guard<std::mutex> lock(mutex);
      done = true;
      finished.notify_all();
    });
    std::unique_lock<std::mutex> lock(mutex);
    while (!finished.wait_for(lock, std::chrono::milliseconds(50), [&] { return done; })) {
      if (interrupted) continue;
      lock.unlock();
      interrupted = check(poll);
      if (interrupted) stop.request();
      lock.lock();
    }
    lock.unlock();
    worker.join();
  }
  if (!interrupted && poll) poll();  // what the work queued after the last check
  if (interrupted) throw py::error_already_set();
  if (failure) std::rethrow_exception(failure);
}

}  // namespace tsm::python
