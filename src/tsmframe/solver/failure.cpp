#include "tsmframe/solver/failure.hpp"

namespace tsm::solver {

Status step_status(const StepFailure& failure) {
  using Reason = StepFailure::Reason;
  switch (failure.reason) {
    case Reason::none: return Status::converged;
    case Reason::singular_tangent:
    case Reason::mechanism:
    case Reason::arc_length_undefined:
    case Reason::controlled_dof_immobile: return Status::singular;
    case Reason::contacts_switching:
    case Reason::contacts_hopping:
    case Reason::contact_passed_through: return Status::contact_chatter;
    case Reason::max_iterations: return Status::max_iterations;
    case Reason::arc_length_no_root:
    case Reason::correction_not_finite:
    case Reason::residual_not_finite:
    case Reason::loads_unresolvable:
    case Reason::end_turned_too_far:
    case Reason::contact_blocked:
    case Reason::blew_up: return Status::diverged;
  }
  return Status::diverged;
}

RunFailure interruption(int step, double load_factor) {
  RunFailure failure;
  failure.kind = RunFailure::Kind::interrupted;
  failure.step = step;
  failure.from = load_factor;
  return failure;
}

bool independent_of_step_size(const StepFailure& failure) {
  // The tangent at the step's start: a smaller step meets it too.
  // A mechanism is the unloaded structure's: no step size changes it.
  return (failure.reason == StepFailure::Reason::controlled_dof_immobile && failure.iteration == 1) ||
         failure.reason == StepFailure::Reason::mechanism;
}

}  // namespace tsm::solver
