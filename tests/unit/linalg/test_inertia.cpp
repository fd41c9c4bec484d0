// The inertia's round-off guard (linalg/inertia.hpp) on its own: a pivot block with an
// eigenvalue below 1e-12 of the diagonal stiffness it came from along its eigenvector is told
// doubtful, with the dof it acts along; an indefinite block whose leading entry is tiny but whose
// eigenvalues are not is not; a dense factorisation of a matrix with an eigenvalue in round-off
// says so, the same matrix shifted clear of zero counts exactly.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "tsmframe/linalg/dense_block_ldlt.hpp"
#include "tsmframe/linalg/inertia.hpp"

namespace {

using tsm::linalg::Inertia;

/// A symmetric 3×3 block with eigenvalues `values` along the columns of a rotation about z by `angle`.
Eigen::Matrix3d block_with(const Eigen::Vector3d& values, double angle) {
  const Eigen::Matrix3d q = Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return q * values.asDiagonal() * q.transpose();
}

TEST(Inertia, APivotWithAnEigenvalueInRoundOffIsDoubtfulAndNamesItsDof) {
  // A column's pivot: transverse stiffness 6.4e17 at the start, a condensed one of −3.6e4 left
  // along ux (5.6e-14 of it), axial and rotational ones clear.
  const Eigen::Vector3d original(6.4e17, 1.0e13, 3.4e10);
  const Eigen::Matrix3d d = Eigen::Vector3d(-3.6e4, 1.0e9, 5.0e6).asDiagonal();
  Inertia inertia;
  tsm::linalg::check_pivot(d, original, 7, inertia);
  EXPECT_EQ(inertia.doubtful, 1);
  EXPECT_FALSE(inertia.known());
  EXPECT_EQ(inertia.row, 7);
  EXPECT_EQ(inertia.component, 0);
  EXPECT_NEAR(inertia.ratio, 3.6e4 / 6.4e17, 1e-20);
  // The same pivot 100 times larger (5.6e-12 of the diagonal) is clear, and so is a rotated one.
  Inertia clear;
  tsm::linalg::check_pivot(Eigen::Vector3d(-3.6e6, 1.0e9, 5.0e6).asDiagonal(), original, 7, clear);
  tsm::linalg::check_pivot(block_with({1.0, -2.0, 3.0}, 0.7), Eigen::Vector3d(2.0, 2.0, 2.0), 8, clear);
  EXPECT_TRUE(clear.known());
  EXPECT_EQ(clear.row, -1);
}

TEST(Inertia, ATinyLeadingEntryOfAClearIndefiniteBlockIsNotDoubtful) {
  // [[ε, 1, 0], [1, ε, 0], [0, 0, 1]]: eigenvalues ε ± 1 and 1, none near zero.
  Eigen::Matrix3d d;
  d << 1e-18, 1.0, 0.0, 1.0, 1e-18, 0.0, 0.0, 0.0, 1.0;
  Inertia inertia;
  tsm::linalg::check_pivot(d, Eigen::Vector3d(1.0, 1.0, 1.0), 0, inertia);
  EXPECT_TRUE(inertia.known());
}

TEST(Inertia, AddingKeepsTheSmallestDoubtfulPivot) {
  Inertia a, b;
  a.negative = 2, a.doubtful = 1, a.row = 3, a.component = 1, a.ratio = 1e-14;
  b.negative = 1, b.doubtful = 2, b.row = 9, b.component = 2, b.ratio = 1e-15;
  a.add(b);
  EXPECT_EQ(a.negative, 3);
  EXPECT_EQ(a.doubtful, 3);
  EXPECT_EQ(a.row, 9);
  EXPECT_EQ(a.component, 2);
  EXPECT_EQ(a.ratio, 1e-15);
}

TEST(Inertia, ADenseFactorisationTellsAnEigenvalueInRoundOffAndCountsAClearOne) {
  // A random positive definite 20-block matrix with its smallest eigenvalue set to ±1e-15 of its
  // scale: the count is doubtful. Set to −0.5 instead: one negative eigenvalue, known.
  std::mt19937 random(11);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  Eigen::MatrixXd g(60, 60);
  for (Eigen::Index i = 0; i < g.size(); ++i) g.data()[i] = value(random);
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(g);
  const Eigen::MatrixXd q = qr.householderQ();
  for (const double smallest : {1e-15, -1e-15, -0.5}) {
    Eigen::VectorXd values = Eigen::VectorXd::LinSpaced(60, 1.0, 10.0);
    values[0] = smallest;
    Eigen::MatrixXd a = q * values.asDiagonal() * q.transpose();
    std::vector<Eigen::Vector3d> original(20);
    for (int j = 0; j < 20; ++j) original[j] = a.diagonal().segment<3>(3 * j);
    tsm::linalg::DenseBlockLDLT ldlt;
    ASSERT_TRUE(ldlt.factorize(a, original.data())) << smallest;
    const Inertia& inertia = ldlt.inertia();
    if (smallest == -0.5) {
      EXPECT_TRUE(inertia.known());
      EXPECT_EQ(inertia.negative, 1);
    } else {
      EXPECT_FALSE(inertia.known()) << smallest;
      EXPECT_LT(inertia.ratio, tsm::linalg::doubtful_pivot);
    }
  }
}

}  // namespace
