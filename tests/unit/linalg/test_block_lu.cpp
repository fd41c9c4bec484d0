// The node-block LU on its own: a random block-sparse matrix with a symmetric pattern and
// non-symmetric values (a tangent with sliding terms), with fill under elimination, factorised
// in place and solved, against Eigen's dense LU of the same matrix; and bit for bit the same on
// one thread and on two.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <limits>
#include <random>
#include <set>
#include <stdexcept>

#include <omp.h>

#include "support/block_patterns.hpp"
#include "tsmframe/linalg/block_lu.hpp"

namespace test_block_lu {
namespace {

using tsm::linalg::Block;
using tsm::linalg::BlockLU;
using tsm::linalg::BlockMatrix;

struct Case {
  BlockMatrix lower;         ///< A's lower triangle, diagonal blocks whole
  std::vector<Block> upper;  ///< A(c, r)ᵀ at each entry (r, c)
  Eigen::MatrixXd dense;
};

// A chain pattern (support/block_patterns.hpp) of `chains` chains and as many couplings between
// them (subtrees of the elimination tree and rows above them); diagonally dominant by `shift`.
Case random_case(int n, int chains, double shift, unsigned seed, bool dense = true) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  const std::vector<std::set<int>> rows = tsm::test::chain_pattern(n, chains, chains, random);
  Case out;
  if (dense) out.dense = Eigen::MatrixXd::Zero(3 * n, 3 * n);
  BlockMatrix& m = out.lower;
  m.size = n;
  m.column.assign(1, 0);
  for (int c = 0; c < n; ++c) {
    for (const int r : rows[c]) {
      Block lower, upper;
      for (int i = 0; i < 9; ++i) lower(i / 3, i % 3) = value(random), upper(i / 3, i % 3) = value(random);
      if (r == c) lower += shift * Block::Identity();
      if (dense) out.dense.block<3, 3>(3 * r, 3 * c) = lower;
      if (dense && r != c) out.dense.block<3, 3>(3 * c, 3 * r) = upper.transpose();
      m.row.push_back(r);
      m.value.push_back(lower);
      out.upper.push_back(upper);
    }
    m.column.push_back(static_cast<int>(m.row.size()));
  }
  return out;
}

// add_fill for both triangles: the filled pattern's entries taken from the case's by (row,
// column); the fill's own entries hold NaN (what a previous factor left: never to be read).
void fill(Case& c) {
  BlockMatrix filled = c.lower;
  tsm::linalg::add_fill(filled);
  const Block stale = Block::Constant(std::numeric_limits<double>::quiet_NaN());
  std::vector<Block> upper(filled.row.size(), stale);
  for (int col = 0; col < filled.size; ++col)
    for (int p = filled.column[col]; p < filled.column[col + 1]; ++p) {
      filled.value[p] = stale;
      for (int q = c.lower.column[col]; q < c.lower.column[col + 1]; ++q)
        if (c.lower.row[q] == filled.row[p]) filled.value[p] = c.lower.value[q], upper[p] = c.upper[q];
    }
  c.lower = filled;
  c.upper = upper;
}

TEST(BlockLU, SolvesANonSymmetricSystemAsTheDenseLUDoes) {
  for (const int chains : {1, 4}) {
    Case c = random_case(240, chains, 6.0, 11u + chains);
    const Eigen::MatrixXd dense = c.dense;
    fill(c);
    BlockLU lu;
    lu.analyze(c.lower);
    ASSERT_TRUE(lu.factorize(c.lower, c.upper));
    std::mt19937 random(3);
    std::uniform_real_distribution<double> value(-1.0, 1.0);
    Eigen::VectorXd b(dense.rows());
    for (Eigen::Index i = 0; i < b.size(); ++i) b[i] = value(random);
    Eigen::VectorXd x = b;
    lu.solve_in_place(x);
    const Eigen::VectorXd exact = dense.partialPivLu().solve(b);
    EXPECT_LT((x - exact).norm(), 1e-10 * exact.norm()) << chains << " chains";
    EXPECT_LT((dense * x - b).norm(), 1e-10 * b.norm()) << chains << " chains";
  }
}

TEST(BlockLU, ANonSymmetricPartIsNotLostToTheSymmetricStorage) {
  // Transposing the off-diagonal couplings changes the solution: the factor reads both triangles.
  Case c = random_case(60, 1, 6.0, 5u);
  Case t = c;
  std::swap(t.lower.value, t.upper);
  for (int col = 0; col < c.lower.size; ++col) t.lower.value[c.lower.column[col]] = c.lower.value[c.lower.column[col]];
  fill(c);
  fill(t);
  BlockLU a, b;
  a.analyze(c.lower);
  b.analyze(t.lower);
  ASSERT_TRUE(a.factorize(c.lower, c.upper));
  ASSERT_TRUE(b.factorize(t.lower, t.upper));
  Eigen::VectorXd x = Eigen::VectorXd::Ones(3 * 60), y = x;
  a.solve_in_place(x);
  b.solve_in_place(y);
  EXPECT_GT((x - y).norm(), 1e-3 * x.norm());
}

TEST(BlockLU, APatternWithoutItsFillIsRefused) {
  Case c = random_case(60, 1, 6.0, 5u);  // random couplings along a chain: fill under elimination
  BlockLU lu;
  EXPECT_THROW(lu.analyze(c.lower), std::logic_error);
}

TEST(BlockLU, ASingularPivotBlockFails) {
  Case c = random_case(30, 1, 0.0, 7u);
  c.lower.value[c.lower.column[0]].setZero();
  fill(c);
  BlockLU lu;
  lu.analyze(c.lower);
  EXPECT_FALSE(lu.factorize(c.lower, c.upper));
}

TEST(BlockLU, OneThreadAndTwoGiveTheSameBits) {
  const int threads = omp_get_max_threads();
  Eigen::VectorXd x[2];
  for (const int t : {1, 2}) {
    omp_set_num_threads(t);
    Case c = random_case(4000, 8, 6.0, 13u, false);
    fill(c);
    BlockLU lu;
    lu.analyze(c.lower);
    ASSERT_TRUE(lu.factorize(c.lower, c.upper));
    x[t - 1] = Eigen::VectorXd::LinSpaced(3 * 4000, -1.0, 1.0);
    lu.solve_in_place(x[t - 1]);
  }
  omp_set_num_threads(threads);
  EXPECT_TRUE(x[0] == x[1]);
}

}  // namespace
}  // namespace test_block_lu
