#pragma once
// A rank-one term u vᵀ of the tangent over the dofs of one element: a contact element's sliding
// term or a follower load's skew term, which the block LDLᵀ's symmetric storage cannot hold
// (the linear solver applies them by Sherman–Morrison–Woodbury).

#include <Eigen/Core>
#include <array>

namespace tsm::linalg {

/// A rank-one term u vᵀ over up to 9 global dofs.
struct RankOne {
  std::array<int, 9> equation{};  ///< free equation of each entry, −1 if constrained
  Eigen::Matrix<double, 9, 1> u, v;
};

}  // namespace tsm::linalg
