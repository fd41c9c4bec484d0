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

/// How close to zero K's eigenvalue along the vector found must be, in shifts (1e-9 of K's
/// largest diagonal entry): a tangent that did not factorise is singular, and round-off in the
/// factor leaves a few shifts; one that did factorise is a mechanism only where its smallest
/// eigenvalue is at round-off level (a slender cantilever's lowest mode reaches 1e-7 of the
/// largest diagonal entry, a mechanism's 1e-16).
inline constexpr double singular_within_shifts = 100.0;
inline constexpr double regular_within_shifts = 1e-3;

/// The null vector of the symmetric tangent `K` (over the free equations, unit length), or an
/// empty vector where K's smallest eigenvalue is more than `within_shifts` shifts from zero.
/// Overwrites K with a factor, and `solver`'s factorisation.
Eigen::VectorXd null_vector(BlockMatrix& K, LinearSolver& solver, int free_count, double within_shifts);

/// Names a free motion `mode` (every dof, global) in `failure` (Reason::mechanism): the nodes that
/// move most and their common direction, or the node that turns where nothing translates.
void name_free_motion(const Model& model, const Eigen::VectorXd& mode, StepFailure& failure);

}  // namespace tsm::solver
