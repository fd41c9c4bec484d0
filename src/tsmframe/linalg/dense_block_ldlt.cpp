#include "tsmframe/linalg/dense_block_ldlt.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace tsm::linalg {
namespace {

constexpr int panel_blocks = 16;  // block columns per panel: 48 scalar columns per product

}  // namespace

int negative_eigenvalues(const Eigen::Matrix3d& d, double c22, double det) {
  const double d00 = d(0, 0);
  if (d00 != 0.0 && c22 != 0.0) return (d00 < 0.0) + (d00 * c22 < 0.0) + (c22 * det < 0.0);
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen;
  eigen.computeDirect(d.selfadjointView<Eigen::Upper>().toDenseMatrix(), Eigen::EigenvaluesOnly);
  return static_cast<int>((eigen.eigenvalues().array() < 0.0).count());
}

bool DenseBlockLDLT::factorize(Eigen::MatrixXd& a, const Eigen::Vector3d* original) {
  const int p = static_cast<int>(a.rows()) / 3;
  for (int j0 = 0; j0 < p; j0 += panel_blocks) {
    const int j1 = std::min(p, j0 + panel_blocks);
    // The panel, column by column (one thread): L(·, j) = z D_j⁻¹ from the running sums z, and
    // the rank-3 update of the panel's later columns; then L(rest, panel) D_panel for the
    // trailing update.
#pragma omp single
    {
      if (j0 == 0) inertia_ = {};
      ok_ = true;
      pivot_.resize(j1 - j0);
      Eigen::Matrix<double, Eigen::Dynamic, 3> z;
      for (int j = j0; j < j1 && ok_; ++j) {
        const Eigen::Matrix3d d = a.block<3, 3>(3 * j, 3 * j).selfadjointView<Eigen::Lower>();
        Eigen::Matrix3d inverse;
        ok_ = invert_pivot(d, inverse, &inertia_.negative);
        if (ok_ && original) check_pivot(d, original[j], j, inertia_);
        const int below = 3 * (p - j - 1), later = 3 * (j1 - j - 1);
        auto l = a.block(3 * (j + 1), 3 * j, below, 3);
        z = l;
        l.noalias() = z * inverse;
        if (later > 0) a.block(3 * (j + 1), 3 * (j + 1), below, later).noalias() -= l * z.topRows(later).transpose();
        a.block<3, 3>(3 * j, 3 * j) = inverse;
        pivot_[j - j0] = d;
      }
      if (ok_ && j1 < p) {
        const int rest = 3 * (p - j1);
        scaled_.resize(rest, 3 * (j1 - j0));
        for (int j = j0; j < j1; ++j)
          scaled_.middleCols<3>(3 * (j - j0)).noalias() = a.block(3 * j1, 3 * j, rest, 3) * pivot_[j - j0];
      }
    }
    if (!ok_) return false;
    // A(r, c) −= L(r, panel) D_panel L(c, panel)ᵀ for r ≥ c beyond the panel, by column panels
    // (their lower part only), shared among the threads.
    const int panels = (p - j1 + panel_blocks - 1) / panel_blocks;
#pragma omp for schedule(dynamic, 1)
    for (int c = 0; c < panels; ++c) {
      const int c0 = j1 + c * panel_blocks, c1 = std::min(p, c0 + panel_blocks), rows = 3 * (p - c0);
      a.block(3 * c0, 3 * c0, rows, 3 * (c1 - c0)).noalias() -=
          a.block(3 * c0, 3 * j0, rows, 3 * (j1 - j0)) * scaled_.middleRows(3 * (c0 - j1), 3 * (c1 - c0)).transpose();
    }
  }
  return true;
}

}  // namespace tsm::linalg
