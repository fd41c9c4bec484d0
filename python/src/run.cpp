// Running: a model given as docs/format.md JSON text, run on `threads` threads with the GIL released
// (Ctrl-C ends it at the next step and raises KeyboardInterrupt: interruptible.hpp); its results
// as numpy arrays (results.cpp).
#include <omp.h>

#include "src/bindings.hpp"
#include "src/interruptible.hpp"
#include "src/results.hpp"

namespace tsm::python {
namespace {

/// The run on `threads` threads (0: as set), on a thread of its own: the caller's setting stays.
solver::RunResult run(const Model& model, int threads) {
  solver::RunResult result;
  run_interruptible([&](const solver::StopRequest* stop) {
    if (threads > 0) omp_set_num_threads(threads);
    result = solver::run_analysis(model, {}, stop);
  });
  return result;
}

py::dict run_json(const std::string& text, int threads) {
  const std::shared_ptr<Model> model = read_model(text);  // kept by the Result for its curves
  return results_dict(model, run(*model, threads));
}

}  // namespace

void define_run(py::module_& module) {
  module.def("run_json", &run_json, py::arg("text"), py::arg("threads") = 0,
             "Run a model given as docs/format.md JSON text; returns a dict of numpy arrays and the results.json text. "
             "Raises ValueError (JSON path: reason) for bad input.");
}

}  // namespace tsm::python
