#pragma once
// The inertia an LDLᵀ factorisation with 3×3 pivot blocks tells of its symmetric matrix
// (Sylvester's law: as many negative eigenvalues as D has), and whether round-off leaves it in
// doubt. A pivot is formed by cancellation: D_k = A_kk − Σ L D Lᵀ, and its rounding error is
// some hundred units in the last place of A_kk's entries. Where an eigenvalue of D_k is smaller
// than `doubtful_pivot` times A_kk's stiffness along its eigenvector, its sign is that error's,
// and so is the count: a member of 10⁴ short elements has a bending stiffness as a whole ~1e-13
// of one element's, and its pivots' signs came out at random as its compression neared buckling.

#include <Eigen/Core>
#include <limits>

namespace tsm::linalg {

/// An eigenvalue of a pivot block below this fraction of its row's diagonal stiffness (along
/// the eigenvector) has no sign to trust. A 10⁴-element column's pivots came out 1.5e-13 of the
/// diagonal off (their sign wrong near buckling); a 10³-element one's are right at 4e-11.
inline constexpr double doubtful_pivot = 1e-12;

struct Inertia {
  int negative = 0;  ///< negative eigenvalues of D (of the matrix, if `doubtful` is 0)
  int doubtful = 0;  ///< eigenvalues of D within round-off of zero: then `negative` is a guess
  /// The smallest such eigenvalue: its block row, the dof of the block it acts most along (0, 1,
  /// 2) and its size against the diagonal stiffness of A along it.
  int row = -1;
  int component = -1;
  double ratio = std::numeric_limits<double>::infinity();

  bool known() const { return doubtful == 0; }
  /// Adds another part's count; the smallest doubtful eigenvalue of both is kept.
  void add(const Inertia& other);
};

/// Whether every eigenvalue μ of a pivot block is clear of zero against the largest entry of the
/// diagonal it came from, read off its inverse: |μ| ≥ 1/‖D⁻¹‖₂ ≥ 1/(3 max |D⁻¹ᵢⱼ|). The
/// factorisation's cheap test, after its inversion; a block it does not clear goes to check_pivot.
inline bool inverse_clear(const Eigen::Matrix3d& inverse, const Eigen::Vector3d& original) {
  return 3.0 * doubtful_pivot * inverse.cwiseAbs().maxCoeff() * original.cwiseAbs().maxCoeff() <= 1.0;
}

/// Checks the pivot block `d` (symmetric, its upper triangle read) of block row `row` against
/// the diagonal of A's block it came from (`original`), adding any eigenvalue within round-off of
/// zero to `inertia`. First cheaply: |μ_min| ≥ |det| / (3 max |cofactor|), for the adjugate's
/// norm is the product of the two larger |μ| and at most 3 times its largest entry; a block that
/// test does not clear against original's largest entry (rarely) is eigen-decomposed. Out of
/// line: the factorisations' own arithmetic (FMA-contracted in their AVX2 clones) stays as it is.
void check_pivot(const Eigen::Matrix3d& d, const Eigen::Vector3d& original, int row, Inertia& inertia);

}  // namespace tsm::linalg
