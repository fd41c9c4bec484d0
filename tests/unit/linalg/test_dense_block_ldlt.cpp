// The dense LDLᵀ with 3×3 pivots (the top separator of the sparse factorisation) on its own:
// random symmetric matrices, definite and indefinite, over several panels, against Eigen's LU;
// the same bits with one thread and two; a singular pivot reported on every thread.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include <omp.h>

#include "tsmframe/linalg/dense_block_ldlt.hpp"

namespace {

using tsm::linalg::DenseBlockLDLT;

Eigen::MatrixXd random_symmetric(int blocks, double shift, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  Eigen::MatrixXd a(3 * blocks, 3 * blocks);
  for (Eigen::Index i = 0; i < a.size(); ++i) a.data()[i] = value(random);
  return (a + a.transpose()) / 2.0 + shift * Eigen::MatrixXd::Identity(3 * blocks, 3 * blocks);
}

/// Factorises with a team of `threads`, every thread calling factorize(); true only if all agree.
bool factorize_with(int threads, Eigen::MatrixXd& a) {
  DenseBlockLDLT ldlt;
  int agreed = 0, failed = 0;
#pragma omp parallel num_threads(threads) reduction(+ : agreed, failed)
  {
    if (ldlt.factorize(a)) ++agreed;
    else ++failed;
  }
  return failed == 0 && agreed == threads;
}

/// x = A⁻¹ b from the factor: L below the diagonal blocks, D⁻¹ on them.
Eigen::VectorXd solve(const Eigen::MatrixXd& f, Eigen::VectorXd b) {
  const int p = static_cast<int>(f.rows()) / 3;
  for (int i = 0; i < p; ++i)
    for (int j = 0; j < i; ++j) b.segment<3>(3 * i) -= f.block<3, 3>(3 * i, 3 * j) * b.segment<3>(3 * j);
  for (int i = 0; i < p; ++i) b.segment<3>(3 * i) = (f.block<3, 3>(3 * i, 3 * i) * b.segment<3>(3 * i)).eval();
  for (int i = p - 1; i >= 0; --i)
    for (int j = i + 1; j < p; ++j) b.segment<3>(3 * i) -= f.block<3, 3>(3 * j, 3 * i).transpose() * b.segment<3>(3 * j);
  return b;
}

TEST(DenseBlockLDLT, SolvesDefiniteAndIndefiniteMatricesOverSeveralPanels) {
  for (const double shift : {20.0, 0.5}) {
    const Eigen::MatrixXd a = random_symmetric(40, shift, 3);  // 40 blocks: panels of 16, 16 and 8
    if (shift < 1.0) ASSERT_LT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(a).eigenvalues().minCoeff(), 0.0);
    Eigen::MatrixXd f = a;
    f.triangularView<Eigen::StrictlyUpper>().setConstant(1e300);  // the upper triangle is never read
    ASSERT_TRUE(factorize_with(1, f));
    const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(a.rows(), -1.0, 2.0);
    const Eigen::VectorXd expected = a.fullPivLu().solve(b);
    EXPECT_LT((solve(f, b) - expected).norm(), 1e-10 * expected.norm()) << "shift " << shift;
  }
}

TEST(DenseBlockLDLT, GivesTheSameBitsWithOneAndTwoThreads) {
  const Eigen::MatrixXd a = random_symmetric(70, 1.0, 5);
  Eigen::MatrixXd one = a, two = a;
  ASSERT_TRUE(factorize_with(1, one));
  ASSERT_TRUE(factorize_with(2, two));
  EXPECT_EQ(one.triangularView<Eigen::Lower>().toDenseMatrix(), two.triangularView<Eigen::Lower>().toDenseMatrix());
}

TEST(DenseBlockLDLT, ReportsASingularPivotOnEveryThread) {
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(6, 6);  // [I I; I I]: the second pivot I − I = 0
  a.block<3, 3>(0, 0).setIdentity();
  a.block<3, 3>(3, 0).setIdentity();
  a.block<3, 3>(3, 3).setIdentity();
  Eigen::MatrixXd b = a;
  EXPECT_FALSE(factorize_with(1, a));
  EXPECT_FALSE(factorize_with(2, b));
}

}  // namespace

namespace {

TEST(DenseBlockLDLT, CountsTheNegativeEigenvaluesOfTheMatrix) {
  // Sylvester: D's inertia is the matrix's (a congruence). 40 blocks over three panels, shifted
  // from definite to indefinite.
  for (const double shift : {20.0, 2.0, 0.0, -2.0}) {
    Eigen::MatrixXd a = random_symmetric(40, shift, 5);
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(a, Eigen::EigenvaluesOnly);
    const int expected = static_cast<int>((eigen.eigenvalues().array() < 0.0).count());
    DenseBlockLDLT ldlt;
    ASSERT_TRUE(ldlt.factorize(a)) << shift;
    EXPECT_EQ(ldlt.negative_pivots(), expected) << "shift " << shift;
    if (shift == 20.0) EXPECT_EQ(expected, 0);
  }
}

}  // namespace
