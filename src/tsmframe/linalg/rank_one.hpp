#pragma once
// A rank-one term u vᵀ of the tangent over the dofs of one element: a contact element's sliding
// term (one per contact point) or a follower load's skew term, which the block LDLᵀ's symmetric
// storage cannot hold (the linear solver applies them by Sherman–Morrison–Woodbury).

#include <Eigen/Core>
#include <vector>

namespace tsm::linalg {

/// A rank-one term u vᵀ over a few global dofs (a contact element's: 3 per node, 6 + 3k).
struct RankOne {
  std::vector<int> equation;  ///< free equation of each entry, −1 if constrained
  Eigen::VectorXd u, v;       ///< one entry per equation entry
  int size() const { return static_cast<int>(equation.size()); }
};

}  // namespace tsm::linalg
