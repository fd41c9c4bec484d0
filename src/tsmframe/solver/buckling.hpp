#pragma once
// Linearised buckling of the unloaded structure under its reference load: the load factors λ at
// which K_M + λ K_G turns singular, K_M the elements' own stiffness at the drawn geometry and
// K_G their geometric stiffness (FORMULATION §1) under the forces of the linear solution for the
// reference load, with the mode shapes — the classical eigenvalue estimate of the critical load,
// beside the nonlinear path. Solved by subspace iteration on K_M's factorisation, so that it
// costs a few solves per mode whatever the model's size.

#include <Eigen/Core>
#include <vector>

#include "tsmframe/model/model.hpp"

namespace tsm::solver {

/// One buckling mode: its critical load factor (> 0: the reference load as given) and shape
/// (every dof, global, scaled to a largest translation of 1, that translation positive).
struct BucklingMode {
  double load_factor = 0.0;
  Eigen::VectorXd shape;
};

/// What linear_buckling found.
struct Buckling {
  std::vector<BucklingMode> modes;  ///< ascending
  /// The next mode found was not resolved in double precision (its stiffness below the
  /// factorisation's round-off): it and those above it are left out.
  bool unresolved = false;
};

/// The `count` lowest positive critical load factors and their modes; fewer where the load
/// compresses too little of the structure to buckle it (none under pure tension), none where
/// the unloaded structure is a mechanism. The model has no contacts, follower loads, prescribed
/// displacements or stages (the reader refuses "buckling" with them).
Buckling linear_buckling(const Model& model, int count);

}  // namespace tsm::solver
