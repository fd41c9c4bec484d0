#pragma once
// Path control: load control in N equal steps, displacement control (λ found so that one dof
// reaches its target in equal increments), with cutback (halve the failed step and retry).

#include <functional>

#include "tsmframe/model/model.hpp"
#include "tsmframe/solver/step_record.hpp"

namespace tsm::solver {

/// Called after every step, converged or failed (progress lines, logging).
using StepObserver = std::function<void(const StepRecord&)>;

/// Runs the model's analysis from the unloaded state. The model must be valid and free of
/// mechanisms (see find_mechanism); non-convergence is reported in the result's status.
RunResult run_analysis(const Model& model, const StepObserver& observer = {});

}  // namespace tsm::solver
