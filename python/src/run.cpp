// Running: a model given as FORMAT.md JSON text, run on `threads` threads with the GIL released;
// its results as numpy arrays (results.cpp).
#include <omp.h>

#include "src/bindings.hpp"
#include "src/results.hpp"

namespace tsm::python {
namespace {

/// The run on `threads` threads (0: as set), for this run only: the caller's setting is restored.
solver::RunResult run(const Model& model, int threads) {
  py::gil_scoped_release release;
  const int callers = omp_get_max_threads();
  if (threads > 0) omp_set_num_threads(threads);
  solver::RunResult result = solver::run_analysis(model);
  omp_set_num_threads(callers);
  return result;
}

py::dict run_json(const std::string& text, int threads) {
  const std::shared_ptr<Model> model = read_model(text);  // kept by the Result for its curves
  return results_dict(model, run(*model, threads));
}

}  // namespace

void define_run(py::module_& module) {
  module.def("run_json", &run_json, py::arg("text"), py::arg("threads") = 0,
             "Run a model given as FORMAT.md JSON text; returns a dict of numpy arrays and the results.json text. "
             "Raises ValueError (JSON path: reason) for bad input.");
}

}  // namespace tsm::python
