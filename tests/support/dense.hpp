#pragma once
// K_ff as a dense matrix for the tests: the node-block tangent (lower triangle, mirrored) mapped
// to the free equations, plus the contact elements' rank-one sliding terms.

#include <Eigen/Dense>
#include <vector>

#include "tsmframe/assembly/dof_map.hpp"
#include "tsmframe/solver/linear_solver.hpp"

namespace tsm::test {

inline Eigen::MatrixXd dense_tangent(const assembly::DofMap& dofs, const linalg::BlockMatrix& a,
                                     const std::vector<linalg::RankOne>& rank_one = {}) {
  const int n = dofs.free_count();
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n);
  for (int c = 0; c < a.size; ++c)
    for (int p = a.column[c]; p < a.column[c + 1]; ++p)
      for (int i = 0; i < 3 && !a.is_fill(p); ++i)
        for (int j = 0; j < 3; ++j) {
          const int r = dofs.equation(3 * dofs.block_node(a.row[p]) + i), q = dofs.equation(3 * dofs.block_node(c) + j);
          if (r < 0 || q < 0) continue;
          K(r, q) += a.value[p](i, j);
          if (a.row[p] != c) K(q, r) += a.value[p](i, j);
        }
  for (const linalg::RankOne& t : rank_one)
    for (int i = 0; i < t.size(); ++i)
      for (int j = 0; j < t.size(); ++j)
        if (t.equation[i] >= 0 && t.equation[j] >= 0) K(t.equation[i], t.equation[j]) += t.u[i] * t.v[j];
  return K;
}

}  // namespace tsm::test
