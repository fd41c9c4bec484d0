// Running: a model given as docs/format.md JSON text, run on `threads` threads with the GIL released
// (Ctrl-C ends it at the next step and raises KeyboardInterrupt: interruptible.hpp); its results
// as numpy arrays (results.cpp).
#include <omp.h>

#include <mutex>
#include <string>
#include <vector>

#include "tsmframe/io/input_error.hpp"
#include "tsmframe/io/json_input.hpp"
#include "tsmframe/io/restart_reader.hpp"
#include "src/bindings.hpp"
#include "src/interruptible.hpp"
#include "src/results.hpp"

namespace tsm::python {
namespace {

/// What a progress callback is told of a step (a dict each): queued by the run's thread, handed
/// to Python by the caller's.
struct StepReport {
  int step = 0, stage = 0, iterations = 0, cutbacks = 0;
  double load_factor = 0.0;
  bool converged = false, cut_back = false;
  std::string message;
};

class ProgressQueue {
 public:
  void push(const solver::StepRecord& s) {
    std::lock_guard<std::mutex> lock(mutex_);
    queued_.push_back({s.step, s.stage + 1, s.iterations, s.cutbacks, s.load_factor, s.converged, s.cut_back, s.message});
  }
  /// Calls `progress` (GIL held) with each queued step, in order.
  void deliver(const py::object& progress) {
    std::vector<StepReport> reports;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      reports.swap(queued_);
    }
    for (const StepReport& r : reports)
      progress(py::dict(py::arg("step") = r.step, py::arg("stage") = r.stage, py::arg("load_factor") = r.load_factor,
                        py::arg("iterations") = r.iterations, py::arg("converged") = r.converged,
                        py::arg("cutbacks") = r.cutbacks, py::arg("cut_back") = r.cut_back, py::arg("message") = r.message));
  }

 private:
  std::mutex mutex_;
  std::vector<StepReport> queued_;
};

/// The run on `threads` threads (0: as set), on a thread of its own: the caller's setting stays.
/// `progress` (None: none) is called with each step as it ends.
solver::RunResult run(const Model& model, int threads, const solver::RestartPoint* from, const py::object& progress) {
  solver::RunResult result;
  ProgressQueue queue;
  const bool reporting = !progress.is_none();
  const solver::StepObserver observer = reporting ? solver::StepObserver([&](const solver::StepRecord& s) { queue.push(s); })
                                                  : solver::StepObserver();
  run_interruptible(
      [&](const solver::StopRequest* stop) {
        if (threads > 0) omp_set_num_threads(threads);
        result = solver::run_analysis(model, observer, stop, from);
      },
      reporting ? std::function<void()>([&] { queue.deliver(progress); }) : std::function<void()>());
  return result;
}

/// `start`: an earlier run's results.json text to go on from (empty: none), at step `step` (0:
/// its newest step with state).
py::dict run_json(const std::string& text, int threads, const std::string& start, int step, const py::object& progress) {
  const std::shared_ptr<Model> model = read_model(text);  // kept by the Result for its curves
  if (start.empty()) return results_dict(model, run(*model, threads, nullptr, progress));
  solver::RestartPoint from;
  try {
    from = io::read_restart(io::parse_json(start), step, *model);
  } catch (const io::InputError& e) {
    throw py::value_error(std::string("start: ") + e.what());
  }
  return results_dict(model, run(*model, threads, &from, progress));
}

}  // namespace

void define_run(py::module_& module) {
  module.def("run_json", &run_json, py::arg("text"), py::arg("threads") = 0, py::arg("start") = "", py::arg("step") = 0,
             py::arg("progress") = py::none(),
             "Run a model given as docs/format.md JSON text; returns a dict of numpy arrays and the results.json text. "
             "Raises ValueError (JSON path: reason) for bad input.");
}

}  // namespace tsm::python
