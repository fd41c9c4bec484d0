#pragma once
// A run: a one-stage model's path (run_stage), or a staged model's stages in turn (stages.hpp).

#include "tsmframe/model/model.hpp"
#include "tsmframe/solver/restart.hpp"
#include "tsmframe/solver/step_record.hpp"
#include "tsmframe/solver/stop_request.hpp"

namespace tsm::solver {

/// Runs the model's analysis from the unloaded state. The model must be valid and free of
/// mechanisms (see find_mechanism); non-convergence is reported in the result's status. `stop`
/// (null: none) is polled before each attempt: once requested, the run ends there, status
/// `interrupted`, every converged step kept.
/// With `from` (restart.hpp), the run goes on from that kept step of an earlier run of the
/// model, its steps numbered on from it.
RunResult run_analysis(const Model& model, const StepObserver& observer = {}, const StopRequest* stop = nullptr,
                       const RestartPoint* from = nullptr);

}  // namespace tsm::solver
