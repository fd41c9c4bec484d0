#pragma once
// How a run (or one step of it) ended. Non-convergence is a status, never an exception.

namespace tsm::solver {

enum class Status {
  converged,       ///< reached the end of the analysis
  diverged,        ///< non-finite or blown-up residual or displacements
  max_iterations,  ///< Newton did not converge within max_iterations
  singular,        ///< the tangent could not be factorised (a limit or bifurcation point)
  cutback_limit,   ///< a step still failed after the allowed number of halvings
  contact_chatter, ///< contacts kept switching on and off within one step
  step_limit,      ///< arc-length control used max_steps before reaching its `until`
  interrupted,     ///< stopped on request at a step boundary (Ctrl-C; stop_request.hpp)
};

/// The spelling used in results.json ("max-iterations", ...).
const char* status_name(Status status);

}  // namespace tsm::solver
