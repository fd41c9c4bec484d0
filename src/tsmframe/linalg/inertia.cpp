#include "tsmframe/linalg/inertia.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace tsm::linalg {

void Inertia::add(const Inertia& other) {
  negative += other.negative;
  doubtful += other.doubtful;
  if (other.ratio < ratio) row = other.row, component = other.component, ratio = other.ratio;
}

namespace {

/// The eigen-decomposition's verdict, for the few blocks the cheap test leaves in question.
void check_eigenvalues(const Eigen::Matrix3d& d, const Eigen::Vector3d& original, int row, Inertia& inertia) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(d.selfadjointView<Eigen::Upper>().toDenseMatrix());
  for (int e = 0; e < 3; ++e) {
    const Eigen::Vector3d v = eigen.eigenvectors().col(e);
    const double stiffness = original.cwiseAbs().dot(v.cwiseAbs2());  // A_kk's diagonal along v
    const double ratio = std::abs(eigen.eigenvalues()[e]) / stiffness;
    if (!(ratio < doubtful_pivot)) continue;
    ++inertia.doubtful;
    if (ratio < inertia.ratio) {
      Eigen::Index component = 0;
      v.cwiseAbs().maxCoeff(&component);
      inertia.row = row, inertia.component = static_cast<int>(component), inertia.ratio = ratio;
    }
  }
}

}  // namespace

void check_pivot(const Eigen::Matrix3d& d, const Eigen::Vector3d& original, int row, Inertia& inertia) {
  const double d00 = d(0, 0), d01 = d(0, 1), d02 = d(0, 2), d11 = d(1, 1), d12 = d(1, 2), d22 = d(2, 2);
  const double c00 = d11 * d22 - d12 * d12, c01 = d02 * d12 - d01 * d22, c02 = d01 * d12 - d02 * d11;
  const double c11 = d00 * d22 - d02 * d02, c12 = d01 * d02 - d00 * d12, c22 = d00 * d11 - d01 * d01;
  const double det = d00 * c00 + d01 * c01 + d02 * c02;
  const double cofactor = std::max({std::abs(c00), std::abs(c01), std::abs(c02), std::abs(c11), std::abs(c12), std::abs(c22)});
  if (std::abs(det) < 3.0 * doubtful_pivot * original.cwiseAbs().maxCoeff() * cofactor) check_eigenvalues(d, original, row, inertia);
}

}  // namespace tsm::linalg
