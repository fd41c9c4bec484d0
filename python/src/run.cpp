// Running: a model given as docs/format.md JSON text, run on `threads` threads with the GIL released
// (Ctrl-C ends it at the next step and raises KeyboardInterrupt: interruptible.hpp); its results
// as numpy arrays (results.cpp).
#include <omp.h>

#include "tsmframe/io/input_error.hpp"
#include "tsmframe/io/json_input.hpp"
#include "tsmframe/io/restart_reader.hpp"
#include "src/bindings.hpp"
#include "src/interruptible.hpp"
#include "src/results.hpp"

namespace tsm::python {
namespace {

/// The run on `threads` threads (0: as set), on a thread of its own: the caller's setting stays.
solver::RunResult run(const Model& model, int threads, const solver::RestartPoint* from) {
  solver::RunResult result;
  run_interruptible([&](const solver::StopRequest* stop) {
    if (threads > 0) omp_set_num_threads(threads);
    result = solver::run_analysis(model, {}, stop, from);
  });
  return result;
}

/// `start`: an earlier run's results.json text to go on from (empty: none), at step `step` (0:
/// its newest step with state).
py::dict run_json(const std::string& text, int threads, const std::string& start, int step) {
  const std::shared_ptr<Model> model = read_model(text);  // kept by the Result for its curves
  if (start.empty()) return results_dict(model, run(*model, threads, nullptr));
  solver::RestartPoint from;
  try {
    from = io::read_restart(io::parse_json(start), step, *model);
  } catch (const io::InputError& e) {
    throw py::value_error(std::string("start: ") + e.what());
  }
  return results_dict(model, run(*model, threads, &from));
}

}  // namespace

void define_run(py::module_& module) {
  module.def("run_json", &run_json, py::arg("text"), py::arg("threads") = 0, py::arg("start") = "", py::arg("step") = 0,
             "Run a model given as docs/format.md JSON text; returns a dict of numpy arrays and the results.json text. "
             "Raises ValueError (JSON path: reason) for bad input.");
}

}  // namespace tsm::python
