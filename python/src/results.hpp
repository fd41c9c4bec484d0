#pragma once
// Results as numpy arrays: a run's model, steps, states and contacts in the shapes Result
// documents (tsmframe/__init__.py), with the CLI's results.json and steps.csv texts.

#include <pybind11/pybind11.h>

#include <memory>

#include "tsmframe/model/model.hpp"
#include "tsmframe/solver/analysis.hpp"

namespace tsm::python {

/// The dict a Result is made from: "model" (kept for its curves), how the run ended, the
/// arrays, and the texts.
pybind11::dict results_dict(const std::shared_ptr<Model>& model, const solver::RunResult& result);

}  // namespace tsm::python
