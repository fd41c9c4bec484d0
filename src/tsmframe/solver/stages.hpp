#pragma once
// A staged analysis (Model::stages): each stage's path run from where the one before ended, what
// earlier stages applied held at their final level (stage_model), the steps numbered through.

#include "tsmframe/model/model.hpp"
#include "tsmframe/solver/restart.hpp"
#include "tsmframe/solver/step_record.hpp"
#include "tsmframe/solver/stop_request.hpp"

namespace tsm::solver {

/// Runs `model`'s stages in turn from the unloaded state, or from a restart point (its stage
/// goes on from there, the steps numbered on from its step). A stage that does not reach its
/// end ends the run there (its status and message, said of the stage), every converged step of
/// it and of the stages before kept.
RunResult run_stages(const Model& model, const StepObserver& observer = {}, const StopRequest* stop = nullptr,
                     const RestartPoint* from = nullptr);


}  // namespace tsm::solver
