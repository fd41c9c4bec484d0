#pragma once
// A point on the equilibrium path: displacements of every dof, the load factor and the
// chord rotation of every element (which makes rotations true totals), and where each contact stands.

#include <Eigen/Core>
#include <vector>

#include "tsmframe/contact/broad_phase.hpp"
#include "tsmframe/contact/contact_state.hpp"

namespace tsm::solver {

/// Arc-length control's memory at a converged state (arc_length_stepping.cpp): what a run
/// restarted there needs to go on as the whole run does.
struct ArcLengthMemory {
  double next_arc = 0.0;               ///< Δs of the next step (0: none yet, the control's first)
  int converged_steps = 0;             ///< the steps taken so far (max_steps counts them)
  Eigen::VectorXd previous_increment;  ///< the last step's ΔD, all dofs: it steers the predictor
  double previous_load_increment = 0.0;
};

struct State {
  Eigen::VectorXd displacements;       ///< (u, v, Θ) per node, all dofs
  double load_factor = 0.0;            ///< λ
  std::vector<double> chord_rotations; ///< β per element
  std::vector<contact::ContactState> contacts;  ///< one per contact of the model
  /// The displacements the contacts' references were taken at (the last converged state, the
  /// first, a restart's), with their fingerprint: where detection's broad phase and the swept
  /// crossings start from in the step that follows. Empty without contacts.
  contact::StepStart contact_references;
  /// How far along its control's path (load and displacement control: λ's path parameter t, the
  /// legs of `path` counted whole; load_stepping.cpp): where a restarted run goes on from.
  double path_parameter = 0.0;
  ArcLengthMemory arc_length;  ///< under arc-length control
};

}  // namespace tsm::solver
