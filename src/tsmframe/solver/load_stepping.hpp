#pragma once
// Load control and displacement control: the path in steps of equal size along each leg of the
// load path (λ: 0 → 1, or through `path`'s points; or the controlled dof to its target), with
// cutback (a failed step is halved and tried again) and the step growing back after it.

#include "tsmframe/assembly/dof_map.hpp"
#include "tsmframe/model/model.hpp"
#include "tsmframe/solver/newton.hpp"
#include "tsmframe/solver/recorder.hpp"
#include "tsmframe/solver/state.hpp"
#include "tsmframe/solver/step_record.hpp"
#include "tsmframe/solver/stop_request.hpp"
#include "tsmframe/solver/tsm_problem.hpp"

namespace tsm::solver {

/// Runs the model's load- or displacement-controlled path from `state` (evaluated: newton.reset)
/// and leaves `state` at the newest converged step. `newton` solves `problem`.
RunResult run_load_stepping(const Model& model, const assembly::DofMap& dofs, NewtonSolver& newton, TsmProblem& problem,
                            State& state, const StepObserver& observer, const StopRequest* stop = nullptr);

}  // namespace tsm::solver
