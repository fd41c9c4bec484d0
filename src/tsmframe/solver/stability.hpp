#pragma once
// The stability of converged equilibria from the tangent's inertia (its negative eigenvalues),
// and the load factor of a bifurcation of the primary path found by bisection on it.

#include <utility>
#include <vector>

#include "tsmframe/solver/newton.hpp"
#include "tsmframe/solver/state.hpp"
#include "tsmframe/solver/step_record.hpp"
#include "tsmframe/solver/tsm_problem.hpp"

namespace tsm::solver {

/// The newest converged step and the one before it (null where there is none).
std::pair<StepRecord*, StepRecord*> newest_converged_two(std::vector<StepRecord>& steps);

/// Whether the tangent's inertia tells the stability of `state`: only where no contact is active
/// (a contact element's sliding term is not symmetric, and the inertia is its symmetric part's).
/// A non-conservative follower load is the other such case; TsmProblem reports no inertia then.
bool inertia_tells_stability(const std::vector<contact::ContactState>& contacts);

/// Whether the newest converged step is unstable and the one before it stable: under load
/// control a bifurcation of the primary path (load control cannot pass a limit point).
bool turned_unstable(const StepRecord* newest, const StepRecord* previous, const RunResult& result);

/// The load factor where the tangent turns indefinite between `previous` (stable) and `newest`
/// (unstable), by bisection on its inertia, each trial equilibrium solved from the newest step's
/// state `from`; recorded in result.critical_points. Leaves the solver evaluated at a trial
/// state: the caller evaluates its own again.
void locate_bifurcation(const StepRecord& newest, const StepRecord& previous, const State& from, NewtonSolver& newton,
                        TsmProblem& problem, RunResult& result);

/// At the end of a run that ended at `state` (the newest converged step's; `evaluated`: the
/// solver's last evaluation was there): the newest step's inertia, which no later attempt took,
/// and under load control a bifurcation between it and the step before.
void close_stability(RunResult& result, State& state, bool evaluated, bool load_control, NewtonSolver& newton,
                     TsmProblem& problem);

}  // namespace tsm::solver
