#pragma once
// A point on the equilibrium path: displacements of every dof, the load factor and the
// chord rotation of every element (which makes rotations true totals), and where each contact stands.

#include <Eigen/Core>
#include <vector>

#include "tsmframe/contact/contact_state.hpp"

namespace tsm::solver {

struct State {
  Eigen::VectorXd displacements;       ///< (u, v, Θ) per node, all dofs
  double load_factor = 0.0;            ///< λ
  std::vector<double> chord_rotations; ///< β per element
  std::vector<contact::ContactState> contacts;  ///< one per contact of the model
  /// How far along its control's path (load and displacement control: λ's path parameter t, the
  /// legs of `path` counted whole; load_stepping.cpp): where a restarted run goes on from.
  double path_parameter = 0.0;
};

}  // namespace tsm::solver
