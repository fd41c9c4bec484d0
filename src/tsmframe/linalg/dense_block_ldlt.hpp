#pragma once
// Dense LDLᵀ with 3×3 pivot blocks, for the block of the tangent where the sparse factor is
// dense: the top of the elimination tree (a frame lattice's last separator), which the
// node-block factorisation (block_ldlt) would otherwise form row by row in indexed 3×3 updates.
// Right-looking in panels of block columns: each panel is factorised column by column, then the
// rest of the matrix is updated by one matrix product per column panel (Eigen's dense kernels).
// No pivoting beyond the 3×3 blocks, like the sparse factorisation: it handles indefinite
// matrices as long as no pivot block is singular.
//
// SPMD: every thread of an OpenMP team calls factorize() together (or one thread, outside any
// parallel region); the column panels of each trailing update are shared among them. The
// panels are fixed by the matrix size alone, so every entry receives the same arithmetic in the
// same order whatever the number of threads: results are bit-identical.

#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "tsmframe/linalg/inertia.hpp"

namespace tsm::linalg {

class DenseBlockLDLT {
 public:
  /// Factorises the symmetric matrix in the lower triangle of `a` (3p × 3p; its strict upper
  /// triangle is ignored and overwritten) in place: below the diagonal blocks L, on them D_j⁻¹
  /// (full 3×3). Returns false (on every thread) if a pivot block is singular or not finite.
  /// With `original` (p entries: the diagonal of each block row of the matrix the pivots came
  /// from, which may be a Schur complement's), pivots within round-off of zero are told.
  bool factorize(Eigen::MatrixXd& a, const Eigen::Vector3d* original = nullptr);
  /// The inertia of D in the last factorisation (its rows: block rows of `a`).
  const Inertia& inertia() const { return inertia_; }
  /// Negative eigenvalues of D in the last factorisation.
  int negative_pivots() const { return inertia_.negative; }

 private:
  std::vector<Eigen::Matrix3d> pivot_;  ///< D_j of the panel being applied
  Eigen::MatrixXd scaled_;              ///< L(rest, panel) D_panel, for the trailing update
  bool ok_ = true;
  Inertia inertia_;
};

/// Negative eigenvalues of the symmetric 3×3 block `d` (upper triangle), from its leading
/// minors d00, c22 = d00 d11 − d01² and det (Sylvester: sign changes in 1, d00, c22, det); a zero
/// leading minor (rare) is settled by the eigenvalues themselves.
int negative_eigenvalues(const Eigen::Matrix3d& d, double c22, double det);

/// D⁻¹ of the symmetric 3×3 block `d` (its upper triangle is read) by cofactors; false if it is
/// singular or not finite. With `negatives`, adds d's negative eigenvalues to it. Shared by
/// both factorisations; inline, for the sparse one's pivot per row is on its critical path.
inline bool invert_pivot(const Eigen::Matrix3d& d, Eigen::Matrix3d& inverse, int* negatives = nullptr) {
  const double d00 = d(0, 0), d01 = d(0, 1), d02 = d(0, 2), d11 = d(1, 1), d12 = d(1, 2), d22 = d(2, 2);
  const double c00 = d11 * d22 - d12 * d12, c01 = d02 * d12 - d01 * d22, c02 = d01 * d12 - d02 * d11;
  const double c11 = d00 * d22 - d02 * d02, c12 = d01 * d02 - d00 * d12, c22 = d00 * d11 - d01 * d01;
  const double det = d00 * c00 + d01 * c01 + d02 * c02;
  if (!(det != 0.0) || !std::isfinite(det)) return false;
  if (negatives && !(d00 > 0.0 && c22 > 0.0 && det > 0.0)) *negatives += negative_eigenvalues(d, c22, det);
  const double r = 1.0 / det;
  inverse << c00 * r, c01 * r, c02 * r,  //
      c01 * r, c11 * r, c12 * r,         //
      c02 * r, c12 * r, c22 * r;
  return inverse.allFinite();
}

}  // namespace tsm::linalg
