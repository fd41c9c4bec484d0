#pragma once
// Linearised buckling under the reference load, at the unloaded structure or at a converged
// state λ₀: the load factors λ = λ₀ + Δλ at which K_T + Δλ K_G turns singular, K_T the tangent
// stiffness at the state (at the unloaded one the elements' own stiffness K_M at the drawn
// geometry) and K_G the elements' geometric stiffness (FORMULATION §1) at the state's chords under
// the force increment of the linear response K_T ΔD = F_ref, with the mode shapes — the classical
// eigenvalue estimate of the critical load, beside the nonlinear path. From a state, the change of
// the chords' geometry along ΔD is left out (exact where the path before buckling is linear, as
// a column's; closer to the path's own critical load the nearer the state). Solved by subspace
// iteration on K_T's factorisation, so that it costs a few solves per mode whatever the size.

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

/// A converged state buckling is estimated from: its step, λ₀, displacements (every dof, global)
/// and chord rotations.
struct BucklingState {
  int step = 0;
  double load_factor = 0.0;
  Eigen::VectorXd displacements;
  std::vector<double> chord_rotations;
};

/// What linear_buckling found.
struct Buckling {
  int step = 0;                     ///< the state it was estimated from (0: the unloaded structure)
  double base_load_factor = 0.0;    ///< λ₀ there
  std::vector<BucklingMode> modes;  ///< ascending
  /// The next mode found was not resolved in double precision (its stiffness below the
  /// factorisation's round-off): it and those above it are left out.
  bool unresolved = false;
};

/// The `count` lowest critical load factors above the state's λ₀ (`at`; none: the unloaded
/// structure, λ₀ = 0) and their modes; fewer where the load compresses too little of the
/// structure to buckle it (none under pure tension), none where the tangent there does not
/// factorise (a mechanism, or a state at a critical point). The model has no contacts, follower
/// loads, prescribed displacements or stages (the reader refuses "buckling" with them).
Buckling linear_buckling(const Model& model, int count, const BucklingState* at = nullptr);

}  // namespace tsm::solver
