#pragma once
// Arc-length control (Crisfield): steps of a given arc length along the path, sized by the
// iterations each takes, cut back where one fails, landing exactly on the `until` target; where
// no arc reaches the path (it jumps), one load-controlled step across.

#include "tsmframe/assembly/dof_map.hpp"
#include "tsmframe/model/model.hpp"
#include "tsmframe/solver/newton.hpp"
#include "tsmframe/solver/recorder.hpp"
#include "tsmframe/solver/state.hpp"
#include "tsmframe/solver/step_record.hpp"
#include "tsmframe/solver/stop_request.hpp"
#include "tsmframe/solver/tsm_problem.hpp"

namespace tsm::solver {

/// Runs the model's arc-length-controlled path from `state` (evaluated: newton.reset) and leaves
/// `state` at the newest converged step. `newton` solves `problem`. A requested `stop` ends the
/// run before the next attempt (status interrupted).
RunResult run_arc_length_stepping(const Model& model, const assembly::DofMap& dofs, NewtonSolver& newton,
                                  TsmProblem& problem, State& state, const StepObserver& observer, const StopRequest* stop = nullptr);

}  // namespace tsm::solver
