#pragma once
// Why a run did not reach its end, as facts: diagnosis.hpp builds every sentence from them, so
// the command line, Python and a study's rows say the same.

#include <string>

namespace tsm::solver {

/// A run that stopped: the step that failed and what cutback and the path found about it.
struct RunFailure {
  enum class Kind {
    none,         ///< the run reached its end
    step_failed,  ///< a step failed at its smallest size (or without cutback)
    step_limit,   ///< arc-length control used max_steps before its `until`
  } kind = Kind::none;
  /// What the step's size measures: λ, the controlled dof, or the arc length.
  enum class Control { load_factor, controlled_displacement, arc_length } control = Control::load_factor;
  int step = 0;
  /// Load and displacement control: the step's λ (or controlled dof) from its start to its
  /// target. Arc-length control: `from` λ at its start, `to` the arc length tried.
  double from = 0.0, to = 0.0;
  int cutbacks = 0;             ///< halvings in a row before the attempt that failed last
  std::string step_message;     ///< why that attempt failed (the Newton step's failure)
  /// The step was already the smallest max_cutbacks halvings of a nominal step allow, after an
  /// earlier failure (cutback could not halve it again).
  bool smallest_step = false;
  int max_cutbacks = 0;
  /// Cutback used all max_cutbacks halvings in a row; `first_step`: on the path's first step.
  bool cutbacks_exhausted = false, first_step = false;
  /// > 0: the load seems to have reached a maximum (a limit point), the current stiffness down to
  /// this fraction of the first step's.
  double limit_point_stiffness = 0.0;
  /// step_limit: the budget, the `until` target and where the watched quantity stands.
  int max_steps = 0;
  double until_value = 0.0, until_now = 0.0;
};

}  // namespace tsm::solver
