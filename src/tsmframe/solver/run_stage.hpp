#pragma once
// One path: the structure set up (dof numbering, assembly, contacts, Newton) and its path followed
// under the model's control — load or displacement (load_stepping) or arc-length
// (arc_length_stepping) — then the newest step's stability and the path's notes.

#include "tsmframe/model/model.hpp"
#include "tsmframe/solver/state.hpp"
#include "tsmframe/solver/step_record.hpp"
#include "tsmframe/solver/stop_request.hpp"

namespace tsm::solver {

/// Runs the path of a one-stage model (no `stages`; stage_model makes one of a staged model's
/// stages) from `state` — empty displacements: the unloaded state — with λ from 0; `state` ends
/// as the newest converged state. The model must be valid and free of mechanisms (see
/// find_mechanism); the state's λ and path parameter say where along the path it starts (a
/// restart; 0 otherwise); non-convergence is reported in the result's status. `stop` (null: none) is
/// polled before each attempt: once requested, the run ends there, status `interrupted`, every
/// converged step kept.
RunResult run_stage(const Model& model, State& state, const StepObserver& observer = {}, const StopRequest* stop = nullptr);

}  // namespace tsm::solver
