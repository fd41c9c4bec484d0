#pragma once
// The motion a singular tangent leaves free: its null vector, by inverse iteration on the tangent
// shifted a little off singular. At the unloaded state the tangent is the elements' own stiffness,
// so that a null vector there is a mechanism — a motion no element resists (hinges in a line, a
// four-hinge portal's sway) — which the supports' check (model/mechanism), looking at connected
// parts as rigid bodies, cannot see.

#include <Eigen/Core>

#include "tsmframe/linalg/block_matrix.hpp"
#include "tsmframe/model/model.hpp"
#include "tsmframe/solver/failure.hpp"
#include "tsmframe/solver/linear_solver.hpp"

namespace tsm::solver {

/// The null vector of the symmetric tangent `K` (over the free equations, unit length), or an
/// empty vector where K is not singular to round-off. Overwrites K with a factor, and `solver`'s
/// factorisation.
Eigen::VectorXd null_vector(BlockMatrix& K, LinearSolver& solver, int free_count);

/// Names a free motion `mode` (every dof, global) in `failure` (Reason::mechanism): the nodes that
/// move most and their common direction, or the node that turns where nothing translates.
void name_free_motion(const Model& model, const Eigen::VectorXd& mode, StepFailure& failure);

}  // namespace tsm::solver
