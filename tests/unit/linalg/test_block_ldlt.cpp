// The node-block LDLᵀ on its own: a random symmetric block-sparse matrix (positive definite, and
// indefinite like a tangent past a limit point) with fill under elimination, factorised in place
// and solved, against Eigen's dense LU of the same matrix.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cstdio>
#include <functional>
#include <random>
#include <set>
#include <stdexcept>

#include <omp.h>

#include "support/block_patterns.hpp"
#include "tsmframe/linalg/block_ldlt.hpp"

namespace test_block_ldlt {
namespace {

using tsm::linalg::Block;
using tsm::linalg::BlockLDLT;
using tsm::linalg::BlockMatrix;
using tsm::test::chain_pattern;

// A block pattern like a frame's: a chain of n blocks plus a few long-range couplings (which
// fill in), lower triangle by columns with the diagonal first; values from a dense symmetric
// matrix built alongside.
struct Case {
  BlockMatrix matrix;
  Eigen::MatrixXd dense;
};

Case random_case(int n, double shift, unsigned seed, int chains = 1, int bridges = 0, bool dense = true, int top = 0) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  const std::vector<std::set<int>> rows = chain_pattern(n, chains, bridges, random, top);
  n += top;
  Case out;
  out.dense = Eigen::MatrixXd::Zero(dense ? 3 * n : 0, dense ? 3 * n : 0);
  std::vector<std::vector<Block>> values(n);
  BlockMatrix& m = out.matrix;
  m.size = n;
  m.column.assign(1, 0);
  for (int c = 0; c < n; ++c) {
    for (const int r : rows[c]) {
      Block b;
      for (int i = 0; i < 9; ++i) b(i / 3, i % 3) = value(random);
      if (r == c) b = (b + b.transpose()).eval() + shift * Block::Identity();
      if (dense) {
        out.dense.block<3, 3>(3 * r, 3 * c) = b;
        out.dense.block<3, 3>(3 * c, 3 * r) = b.transpose();
      }
      values[c].push_back(b);
      m.row.push_back(r);
    }
    m.column.push_back(static_cast<int>(m.row.size()));
  }
  // Fill in the pattern, then put the values where they belong (fill entries stay zero).
  const BlockMatrix original = m;
  tsm::linalg::add_fill(m);
  for (int c = 0; c < n; ++c)
    for (int p = original.column[c]; p < original.column[c + 1]; ++p) {
      const auto first = m.row.begin() + m.column[c], last = m.row.begin() + m.column[c + 1];
      m.value[std::lower_bound(first, last, original.row[p]) - m.row.begin()] = values[c][p - original.column[c]];
    }
  return out;
}

// A x for the (unfactorised) lower-triangle block matrix.
Eigen::VectorXd multiply(const BlockMatrix& m, const Eigen::VectorXd& x) {
  Eigen::VectorXd y = Eigen::VectorXd::Zero(x.size());
  for (int c = 0; c < m.size; ++c)
    for (int p = m.column[c]; p < m.column[c + 1]; ++p) {
      const int r = m.row[p];
      y.segment<3>(3 * r) += m.value[p] * x.segment<3>(3 * c);
      if (r != c) y.segment<3>(3 * c) += m.value[p].transpose() * x.segment<3>(3 * r);
    }
  return y;
}

void expect_solves(const Case& c) {
  BlockMatrix m = c.matrix;
  BlockLDLT ldlt;
  ldlt.analyze(m);
  ASSERT_TRUE(ldlt.factorize(m));
  std::mt19937 random(7);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  Eigen::VectorXd b(c.dense.rows());
  for (Eigen::Index i = 0; i < b.size(); ++i) b[i] = value(random);
  const Eigen::VectorXd expected = c.dense.fullPivLu().solve(b);
  Eigen::VectorXd x = b;
  ldlt.solve_in_place(x);
  EXPECT_LT((x - expected).norm(), 1e-9 * expected.norm());
  EXPECT_LT((c.dense * x - b).norm(), 1e-10 * (c.dense.norm() * x.norm()));
}

TEST(BlockLDLT, AddFillKeepsTheEntriesAndAddsWhatEliminationNeeds) {
  const Case c = random_case(60, 20.0, 1);
  const BlockMatrix& m = c.matrix;
  // Every column starts with its diagonal and lists rows ascending; the filled pattern is closed
  // under elimination, which analyze() checks (it throws otherwise).
  for (int col = 0; col < m.size; ++col) {
    ASSERT_EQ(m.row[m.column[col]], col);
    EXPECT_TRUE(std::is_sorted(m.row.begin() + m.column[col], m.row.begin() + m.column[col + 1]));
  }
  BlockLDLT ldlt;
  EXPECT_NO_THROW(ldlt.analyze(m));
  // Without its fill the same matrix is refused.
  BlockMatrix chain;
  chain.size = 3;
  chain.column = {0, 3, 4, 5};  // column 0 couples blocks 1 and 2, which then fill in (2, 1)
  chain.row = {0, 1, 2, 1, 2};
  chain.value.assign(5, Block::Identity());
  EXPECT_THROW(ldlt.analyze(chain), std::logic_error);
  tsm::linalg::add_fill(chain);
  EXPECT_EQ(chain.row.size(), 6u);
  EXPECT_EQ(chain.fill, (std::vector<unsigned char>{0, 0, 0, 0, 1, 0}));  // only (2, 1) is new
  EXPECT_NO_THROW(ldlt.analyze(chain));
}

TEST(BlockLDLT, SolvesPositiveDefiniteSystemsWithFill) {
  for (unsigned seed = 1; seed <= 5; ++seed) expect_solves(random_case(80, 20.0, seed));
}

TEST(BlockLDLT, SolvesIndefiniteSystems) {
  // A small shift leaves the matrix indefinite (as a tangent past a limit point).
  for (unsigned seed = 11; seed <= 15; ++seed) {
    const Case c = random_case(40, 0.5, seed);
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(c.dense);
    ASSERT_LT(eigen.eigenvalues().minCoeff(), 0.0);
    expect_solves(c);
  }
}

TEST(BlockLDLT, CountsTheNegativeEigenvaluesOfTheMatrix) {
  // Sylvester: D has as many negative eigenvalues as the matrix (LDLᵀ is a congruence), which is
  // how a run tells a tangent past a limit point. Positive definite: none; shifted down: the
  // dense eigenvalues' count, with one thread and two, the dense top separator included.
  for (unsigned seed = 21; seed <= 25; ++seed) {
    const Case definite = random_case(60, 20.0, seed);
    BlockMatrix m = definite.matrix;
    BlockLDLT ldlt;
    ldlt.analyze(m);
    ASSERT_TRUE(ldlt.factorize(m));
    EXPECT_EQ(ldlt.negative_pivots(), 0);
    const Case c = random_case(60, 0.5, seed);
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(c.dense);
    const int expected = static_cast<int>((eigen.eigenvalues().array() < 0.0).count());
    ASSERT_GT(expected, 0);
    BlockMatrix n = c.matrix;
    ldlt.analyze(n);
    ASSERT_TRUE(ldlt.factorize(n));
    EXPECT_EQ(ldlt.negative_pivots(), expected) << "seed " << seed;
  }
  // With the rows above the subtrees in parallel and a dense top separator (too big for a dense
  // eigensolver in a unit test; DenseBlockLDLT's own count is checked in its tests): shifted so
  // that some pivots are negative, the same count with one thread and two.
  const Case big = random_case(3600, 1.0, 9, 24, 60, false, 48);
  int counted[2] = {-1, -1};
  for (int threads = 1; threads <= 2; ++threads) {
    omp_set_num_threads(threads);
    BlockMatrix m = big.matrix;
    BlockLDLT ldlt;
    ldlt.analyze(m);
    ASSERT_GE(ldlt.rows_in_dense_paths(), 48);
    ASSERT_TRUE(ldlt.factorize(m));
    counted[threads - 1] = ldlt.negative_pivots();
  }
  omp_set_num_threads(omp_get_num_procs());
  EXPECT_GT(counted[0], 0);
  EXPECT_EQ(counted[0], counted[1]);
}

// Solves c with one thread and with two, each by a plain solve and with the forward
// substitution along the factorisation; `check` looks at the analysis first. Expects residuals
// below 1e-12 and the same bits from both thread counts.
void expect_the_same_with_one_and_two_threads(const Case& c, unsigned seed, const std::function<void(const BlockLDLT&)>& check) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  Eigen::VectorXd b(3 * c.matrix.size);
  for (Eigen::Index i = 0; i < b.size(); ++i) b[i] = value(random);
  Eigen::VectorXd x[2], fused[2];
  for (int threads = 1; threads <= 2; ++threads) {
    omp_set_num_threads(threads);
    BlockMatrix m = c.matrix;
    BlockLDLT ldlt;
    ldlt.analyze(m);
    check(ldlt);
    ASSERT_TRUE(ldlt.factorize(m));
    x[threads - 1] = b;
    ldlt.solve_in_place(x[threads - 1]);
    // The forward substitution along the factorisation, the rest after it.
    BlockMatrix n = c.matrix;
    fused[threads - 1] = b;
    ASSERT_TRUE(ldlt.factorize(n, &fused[threads - 1]));
    ldlt.finish_solve(fused[threads - 1]);
  }
  omp_set_num_threads(omp_get_num_procs());
  const double residual = (multiply(c.matrix, x[0]) - b).norm() / b.norm();
  std::printf("[figure] block LDLT, %d blocks in parallel subtrees: relative residual %.2e\n", c.matrix.size, residual);
  EXPECT_LT(residual, 1e-12);
  EXPECT_LT((multiply(c.matrix, fused[0]) - b).norm() / b.norm(), 1e-12);
  EXPECT_EQ(x[0], x[1]);  // bit for bit
  EXPECT_EQ(fused[0], fused[1]);
}

TEST(BlockLDLT, SolvesWithParallelSubtreesAndRowsAboveThemTheSameWithAnyThreadCount) {
  // 24 chains of 150 blocks: subtrees of 64 … n/16 blocks are factorised and solved as parallel
  // tasks; the bridges between chains put rows above them, in levels and in paths of the tree
  // (whose rows are formed in three passes, the first two in parallel).
  expect_the_same_with_one_and_two_threads(random_case(3600, 20.0, 3, 24, 60, false), 5, [](const BlockLDLT& ldlt) {
    ASSERT_GT(ldlt.task_count(), 4);
    ASSERT_GE(ldlt.rows_above_tasks(), 256);  // enough to run them level by level in parallel
    ASSERT_GE(ldlt.rows_in_paths(), 256);     // and paths of the tree among them, formed in passes
  });
}

TEST(BlockLDLT, FactorisesADenseTopSeparatorAsOneDenseMatrixTheSameWithAnyThreadCount) {
  // The chains above plus 48 blocks, all coupled among themselves, numbered last: their rows end
  // the tree's top path with consecutive numbers and fill their triangle, so after the passes
  // over their prefixes they are factorised as one dense matrix (DenseBlockLDLT).
  expect_the_same_with_one_and_two_threads(random_case(3600, 20.0, 3, 24, 60, false, 48), 9, [](const BlockLDLT& ldlt) {
    ASSERT_GE(ldlt.rows_in_dense_paths(), 48);
  });
}

TEST(BlockLDLT, NeverReadsTheFillEntriesOfTheMatrix) {
  // The assembly rewrites only the entries of A between factorisations: the fill still holds the
  // last factor. A second factorisation must give the same bits as the first.
  const Case c = random_case(3600, 20.0, 3, 24, 60, false, 48);
  ASSERT_FALSE(c.matrix.fill.empty());
  BlockMatrix m = c.matrix;
  BlockLDLT ldlt;
  ldlt.analyze(m);
  ASSERT_TRUE(ldlt.factorize(m));
  const BlockMatrix first = m;
  for (size_t p = 0; p < m.value.size(); ++p)
    if (!m.is_fill(static_cast<int>(p))) m.value[p] = c.matrix.value[p];
  ASSERT_TRUE(ldlt.factorize(m));
  for (size_t p = 0; p < m.value.size(); ++p) ASSERT_EQ(m.value[p], first.value[p]) << "entry " << p;
}

TEST(BlockLDLT, ReportsASingularPivot) {
  BlockMatrix m;
  m.size = 2;
  m.column = {0, 2, 3};
  m.row = {0, 1, 1};
  m.value = {Block::Identity(), Block::Identity(), Block::Identity()};  // the Schur complement I − I = 0
  tsm::linalg::add_fill(m);
  m.value = {Block::Identity(), Block::Identity(), Block::Identity()};
  BlockLDLT ldlt;
  ldlt.analyze(m);
  EXPECT_FALSE(ldlt.factorize(m));
}

}  // namespace

}  // namespace test_block_ldlt
