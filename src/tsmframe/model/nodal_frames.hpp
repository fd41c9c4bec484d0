#pragma once
// The frames the unknowns are solved in, node by node: the global (x, y) but at a skew roller
// (Model::skew_rollers), whose translations are (t, n) along and normal to its plane, so that
// holding n is holding a dof. A node's 3×3 frame T has the roller's (t, n) as the columns of its
// translations (det T = 1) and turns no rotation: global d = T d_nodal, nodal f = Tᵀ f_global,
// nodal K = T_aᵀ K T_b. The solver's state, forces and tangent are nodal; elements, contacts and
// results are global.

#include <Eigen/Core>
#include <span>
#include <vector>

#include "tsmframe/model/model.hpp"

namespace tsm {

class NodalFrames {
 public:
  explicit NodalFrames(const Model& model);

  bool empty() const { return nodes_.empty(); }
  /// The nodes whose frames are turned, ascending.
  const std::vector<int>& nodes() const { return nodes_; }
  bool turned(int node) const { return !empty() && frame_of_[node] >= 0; }
  /// The node's T (identity where it is not turned).
  Eigen::Matrix3d frame(int node) const;

  /// d ← T d at every turned node (nodal → global: displacements, reactions), all dofs.
  void to_global(Eigen::VectorXd& all_dofs) const;
  /// f ← Tᵀ f at every turned node (global → nodal: forces, loads, displacements read back).
  void to_nodal(Eigen::VectorXd& all_dofs) const;
  /// f ← Tᵀ f over one element's dofs `dofs` (a node's ux followed by its uy, as the elements
  /// and contacts list them): a rank-one term's vectors.
  void to_nodal(std::span<const int> dofs, Eigen::Ref<Eigen::VectorXd> values) const;
  /// The block K(a, b) turned: T_aᵀ K T_b.
  Eigen::Matrix3d to_nodal(int node_a, int node_b, const Eigen::Matrix3d& block) const;
  /// The nodal equation's share of a global translation or rotation dof's row: the weight by which
  /// a global row `dof` joins the nodal row of the same node's dof `nodal_dof` (t for ux and uy at
  /// a turned node, with t's component; the dof itself, 1, elsewhere).
  struct Share {
    int nodal_dof = 0;
    double weight = 1.0;
  };
  Share row_share(int dof) const;

 private:
  std::vector<int> nodes_;
  std::vector<Eigen::Vector2d> along_;  ///< per turned node, its t (n = (−t_y, t_x))
  std::vector<int> frame_of_;           ///< per node: index into along_, −1 (empty when none is turned)
};

}  // namespace tsm
