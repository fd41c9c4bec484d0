#pragma once
// Linear springs from nodes to the ground (Model::springs, docs/format.md "springs"): a
// translation spring of stiffness k along a fixed unit direction d pulls its node back with
// −k d (d·u) and adds k d dᵀ to the node's block; a rotation spring −k θ and k. Conservative and
// linear: their tangent is exact at every state.

#include <Eigen/Core>
#include <vector>

#include "tsmframe/assembly/dof_map.hpp"
#include "tsmframe/model/model.hpp"

namespace tsm::assembly {

class NodalSprings {
 public:
  NodalSprings(const Model& model, const DofMap& dofs) : model_(model), dofs_(dofs) {}
  bool empty() const { return model_.springs.empty(); }

  /// Adds the springs' forces k d (d·u) (k θ) at `displacements` to the internal force `out`
  /// (all dofs); with `only`, just at the nodes marked there.
  void add_forces(const Eigen::VectorXd& displacements, const std::vector<char>* only, Eigen::VectorXd& out) const;

  /// add(node, node, K) for each spring's block (in the model's spring order), and each
  /// block's coupling of free to prescribed dofs times the prescribed increments into
  /// `prescribed_coupling` (over the free equations; empty: nothing prescribed); with `only`,
  /// just the springs at nodes marked there.
  template <class Add>
  void add_blocks(const std::vector<char>* only, Eigen::VectorXd& prescribed_coupling, Add&& add) const {
    for (const NodalSpring& s : model_.springs) {
      if (only && !(*only)[s.node]) continue;
      const Eigen::Matrix3d k = block(s);
      add(s.node, s.node, k);
      if (prescribed_coupling.size() == 0) continue;
      for (int b = 0; b < dofs_per_node; ++b) {
        const double dp = model_.prescribed(dofs_per_node * s.node + b);
        if (dp == 0.0 || dofs_.equation(dofs_per_node * s.node + b) >= 0) continue;
        for (int a = 0; a < dofs_per_node; ++a)
          if (const int row = dofs_.equation(dofs_per_node * s.node + a); row >= 0) prescribed_coupling[row] += k(a, b) * dp;
      }
    }
  }

 private:
  /// The spring's 3×3 block on its node's (u, v, θ).
  static Eigen::Matrix3d block(const NodalSpring& s);

  const Model& model_;
  const DofMap& dofs_;
};

}  // namespace tsm::assembly
