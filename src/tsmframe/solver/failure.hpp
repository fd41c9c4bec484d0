#pragma once
// Why a run did not reach its end, as facts: diagnosis.hpp builds every sentence from them, so
// the command line, Python and a study's rows say the same.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "tsmframe/assembly/global_system.hpp"
#include "tsmframe/solver/status.hpp"

namespace tsm::solver {

/// Why a Newton step failed, with the facts a sentence about it needs (node, element and contact
/// indices, not ids: diagnosis.hpp names them).
struct StepFailure {
  enum class Reason {
    none,                     ///< the step converged
    singular_tangent,         ///< the tangent could not be factorised
    arc_length_undefined,     ///< arc-length control: the load moves no translation
    arc_length_no_root,       ///< arc-length control: the constraint has no real root
    controlled_dof_immobile,  ///< displacement control: the controlled dof does not move under the load
    correction_not_finite,
    contacts_switching,       ///< contacts kept switching on and off within the step
    contacts_hopping,         ///< contact points kept hopping back and forth between elements
    residual_not_finite,
    loads_unresolvable,       ///< the residual stays at the rounding level of the internal forces
    contact_passed_through,   ///< a contact node passed through a beam after its contact was released
    end_turned_too_far,       ///< an element end turned past a right angle against its chord
    contact_blocked,          ///< a contact node reached an element a contact of the other frame is on
    mechanism,                ///< the unloaded tangent is singular: a motion no element resists (free_mode.hpp)
    blew_up,                  ///< the unbalanced force or the displacements ran away
    max_iterations,
  } reason = Reason::none;
  int iteration = 0;  ///< the iterate it failed at (max_iterations: the budget)
  bool hinged = false;    ///< singular_tangent: some member end is released (a mechanism among hinges)
  bool contacts = false;  ///< controlled_dof_immobile: the model has contacts (one still open may be why)
  /// contacts_hopping: the contact that hops (index) and the beam node it hops across; −1 unknown.
  int hopping_contact = -1, hop_node = -1;
  double relative_residual = 0.0;  ///< loads_unresolvable, max_iterations: the last relative residual
  assembly::RoundingFloor floor;   ///< loads_unresolvable: the rounding floor and the contact that rounds most
  double end_rotation = 0.0;       ///< end_turned_too_far: the largest end rotation against a chord
  /// contact_blocked: the contact (index) that reached `element`, and the contact on it (−1: none found).
  int blocked_contact = -1, element = -1, holding_contact = -1;
  /// max_iterations: converged iterates whose contacts did not settle, and the model's contact nodes.
  int unsettled = 0, contact_nodes = 0;
  /// The structure is held only by contacts resting on it, and this one (index) let go or slid
  /// off the beam's end: said first, as the cause of what Newton then met. −1: not so.
  int lost_resting_contact = -1;
  bool resting_contact_slid_off = false;
  /// mechanism: the nodes that move most in the free motion (indices, by id, at most 3), how
  /// many move that much, and their common direction (zero: none); `turning_only`: nothing
  /// translates, the one node listed turns.
  std::vector<int> moving_nodes;
  int moving_count = 0;
  Eigen::Vector2d moving_direction = Eigen::Vector2d::Zero();
  bool turning_only = false;
};

/// The status a failed step reports.
Status step_status(const StepFailure& failure);
/// Whether a smaller step cannot help: the step failed at its first iterate for a reason its
/// size does not change (the controlled dof does not move under the load at the step's start).
bool independent_of_step_size(const StepFailure& failure);

/// A run that stopped: the step that failed and what cutback and the path found about it.
struct RunFailure {
  enum class Kind {
    none,         ///< the run reached its end
    step_failed,  ///< a step failed at its smallest size (or without cutback)
    step_limit,   ///< arc-length control used max_steps before its `until`
    interrupted,  ///< a stop request ended it before step `step`, `from` the newest converged λ
  } kind = Kind::none;
  /// What the step's size measures: λ, the controlled dof, or the arc length.
  enum class Control { load_factor, controlled_displacement, arc_length } control = Control::load_factor;
  int step = 0;
  /// Load and displacement control: the step's λ (or controlled dof) from its start to its
  /// target. Arc-length control: `from` λ at its start, `to` the arc length tried.
  double from = 0.0, to = 0.0;
  int cutbacks = 0;             ///< halvings in a row before the attempt that failed last
  StepFailure step_failure;     ///< why that attempt failed
  /// The step was the smallest max_cutbacks halvings of a nominal step allow, with fewer than
  /// max_cutbacks halvings in a row (reached since an earlier failure, or now): cutback could not
  /// halve it again.
  bool smallest_step = false;
  int max_cutbacks = 0;
  /// Cutback used all max_cutbacks halvings in a row; `first_step`: on the path's first step.
  bool cutbacks_exhausted = false, first_step = false;
  /// > 0: the load seems to have reached a maximum (a limit point), the current stiffness down to
  /// this fraction of the first step's; `limit_point_ahead`: its square, run on linearly in λ
  /// through the two newest converged states, reaches nil within the failed step.
  double limit_point_stiffness = 0.0;
  bool limit_point_ahead = false;
  /// step_limit: the budget, the `until` target and where the watched quantity stands.
  int max_steps = 0;
  double until_value = 0.0, until_now = 0.0;
};

/// The facts of a run a stop request ended before step `step`, its newest converged step at λ
/// `load_factor`.
RunFailure interruption(int step, double load_factor);

}  // namespace tsm::solver
