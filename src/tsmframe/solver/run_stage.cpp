#include "tsmframe/solver/run_stage.hpp"

#include <utility>
#include <vector>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include "tsmframe/assembly/dof_map.hpp"
#include "tsmframe/assembly/global_system.hpp"
#include "tsmframe/solver/arc_length_stepping.hpp"
#include "tsmframe/solver/load_stepping.hpp"
#include "tsmframe/solver/newton.hpp"
#include "tsmframe/solver/path_notes.hpp"
#include "tsmframe/solver/stability.hpp"
#include "tsmframe/solver/tsm_problem.hpp"
#include "tsmframe/util/first_touch.hpp"

namespace tsm::solver {

RunResult run_stage(const Model& model, State& state, const StepObserver& observer, const StopRequest* stop) {
  const AnalysisSettings& settings = model.analysis;
  const Control& control = settings.control;
  assembly::DofMap dofs(model);
  assembly::GlobalSystem system(model, dofs);
  const contact::ContactSet contacts(model);
  TsmProblem problem(system, &contacts);
  NewtonSolver newton(problem, {settings.tolerance, settings.max_iterations});
#if defined(__GLIBC__)
  // The set-up's temporaries (node graph, ordering, fill, tasks) are freed by now but scattered
  // through the heap, where the run's vectors do not fill them: hand their pages back (at 10⁵
  // elements ~3 MB of the peak resident memory, once per run).
  malloc_trim(0);
#endif

  if (state.displacements.size() == 0) {  // the unloaded state
    std::vector<double> zero_rotations;
    util::assign_touched(zero_rotations, model.elements.size(), 0.0);
    state = State{};
    state.displacements = util::zeros_touched(model.dof_count());
    state.chord_rotations = std::move(zero_rotations);
    state.contacts = contacts.initial_states();
  }
  problem.take_contact_references(state);  // a restart's
  newton.reset(state);
  RunResult result = control.type == ControlType::arc_length
                         ? run_arc_length_stepping(model, dofs, newton, problem, state, observer, stop)
                         : run_load_stepping(model, dofs, newton, problem, state, observer, stop);
  // The newest converged step's inertia: each other step's came with the attempt that started
  // from it. `state` is that step's (every run ends there); the last evaluation was made there
  // unless the run ended on a failed attempt. (A run interrupted before its first step has none.)
  const bool evaluated = result.steps.empty() || result.steps.back().converged;
  close_stability(result, state, evaluated, control.type == ControlType::load, newton, problem);
  close_path(model, result, control.type);
  return result;
}

}  // namespace tsm::solver
