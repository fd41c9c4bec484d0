#pragma once
// Global internal force vector and tangent of the whole structure at a given displacement
// state. The sparsity pattern of K_ff is built once; every evaluation only writes values.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "tsmframe/assembly/dof_map.hpp"
#include "tsmframe/element/beam_element.hpp"
#include "tsmframe/model/model.hpp"

namespace tsm::assembly {

using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

/// What one evaluation of the structure yields.
struct Evaluation {
  Eigen::VectorXd internal_force;        ///< F = Σ J S over all dofs
  Eigen::VectorXd element_forces;        ///< (N, M_i, M_j) per element, stacked
  std::vector<double> chord_rotations;   ///< β per element at this state
  /// K_fp · D_p,ref over the free equations: how the tangent couples free dofs to the
  /// prescribed displacements (for the tangent predictor, FORMULATION §4).
  Eigen::VectorXd prescribed_coupling;
  /// Estimated rounding error of the assembled internal forces, per kind (2-norm over dofs,
  /// element errors taken as independent): the floor under any residual at this state.
  double force_floor = 0.0;
  double moment_floor = 0.0;
};

class GlobalSystem {
 public:
  GlobalSystem(const Model& model, const DofMap& dofs);

  const Model& model() const { return model_; }
  const DofMap& dofs() const { return dofs_; }

  /// Evaluates every element at `displacements` (all dofs), continuing each chord rotation from
  /// `previous_rotations`. With `with_tangent`, K_ff (see tangent()) is overwritten.
  void evaluate(const Eigen::VectorXd& displacements, const std::vector<double>& previous_rotations,
                bool with_tangent, Evaluation& out);

  /// The tangent over the free equations, K_ff, from the last evaluation with tangent.
  const SparseMatrix& tangent() const { return tangent_; }

 private:
  const Model& model_;
  const DofMap& dofs_;
  std::vector<element::InitialChord> initial_;
  SparseMatrix tangent_;
  /// For element e, entry (a, b) of its 6×6 tangent goes to tangent_.valuePtr()[slots_[36e + 6b + a]]
  /// (−1 where a or b is constrained).
  std::vector<int> slots_;
  bool has_prescribed_ = false;
};

}  // namespace tsm::assembly
