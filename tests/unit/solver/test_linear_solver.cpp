// The Newton iteration's linear solver on its own, every path against a dense solve of
// K_ff = A + Σ u vᵀ: the in-place block LDLᵀ alone; a few sliding terms by Woodbury; more than
// 32 by the block LU, or by SparseLU where a term lies outside the tangent's blocks; and A singular on its own but not with its sliding term (the SparseLU
// fallback asks for the tangent again after the failed in-place factorisation).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "support/dense.hpp"
#include "support/models.hpp"
#include "tsmframe/assembly/global_system.hpp"
#include "tsmframe/solver/linear_solver.hpp"

namespace {

using namespace tsm::test;
using tsm::linalg::Block;
using tsm::linalg::BlockMatrix;
using tsm::linalg::RankOne;

struct Setup {
  tsm::Model model;
  std::unique_ptr<tsm::assembly::DofMap> dofs;
  BlockMatrix tangent;  // the pattern of a 30-element cantilever (with its fill), random values
};

std::unique_ptr<Setup> setup(unsigned seed, double shift, const char* support = "fixed") {
  auto s = std::make_unique<Setup>();
  BeamSpec b;
  b.divisions = 30;
  json m = beam_model(b);
  m["supports"] = json::array({{{"node", 1}, {"type", support}}});
  if (std::string(support) == "pinned") m["supports"].push_back({{"node", 2}, {"type", "roller-x"}});
  s->model = tsm::io::read_model(m);
  s->dofs = std::make_unique<tsm::assembly::DofMap>(s->model);
  tsm::assembly::GlobalSystem system(s->model, *s->dofs);
  s->tangent = system.tangent();
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  for (int c = 0; c < s->tangent.size; ++c)
    for (int p = s->tangent.column[c]; p < s->tangent.column[c + 1]; ++p) {
      Block v;
      for (int i = 0; i < 9; ++i) v(i / 3, i % 3) = value(random);
      if (s->tangent.row[p] == c) v = (v + v.transpose()).eval() + shift * Block::Identity();
      // A constrained dof inside a block carries no equation: zero row and column, 1 on the
      // diagonal (as GlobalSystem leaves it).
      const int row_node = s->dofs->block_node(s->tangent.row[p]), column_node = s->dofs->block_node(c);
      for (int d = 0; d < 3; ++d) {
        if (s->model.constrained[3 * row_node + d]) v.row(d).setZero();
        if (s->model.constrained[3 * column_node + d]) v.col(d).setZero();
        if (s->tangent.row[p] == c && s->model.constrained[3 * row_node + d]) v(d, d) = 1.0;
      }
      s->tangent.value[p] = v;
    }
  return s;
}

std::vector<RankOne> rank_ones(const tsm::assembly::DofMap& dofs, int count, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> value(-0.3, 0.3);
  std::uniform_int_distribution<int> equation(0, dofs.free_count() - 1);
  std::vector<RankOne> terms(count);
  for (RankOne& t : terms) {
    t.equation.resize(9);
    t.u.resize(9);
    t.v.resize(9);
    for (int a = 0; a < 9; ++a) {
      t.equation[a] = a == 8 ? -1 : equation(random);  // one entry on a constrained dof
      t.u[a] = value(random);
      t.v[a] = value(random);
    }
  }
  return terms;
}

// Terms on the dofs of an element's two nodes each (a contact element's), whose blocks the
// tangent has: the block LU takes them.
std::vector<RankOne> element_rank_ones(const tsm::Model& model, const tsm::assembly::DofMap& dofs, int count, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> value(-0.3, 0.3);
  std::uniform_int_distribution<int> element(0, static_cast<int>(model.elements.size()) - 1);
  std::vector<RankOne> terms(count);
  for (RankOne& t : terms) {
    const tsm::Element& e = model.elements[element(random)];
    t.u.resize(6);
    t.v.resize(6);
    for (int a = 0; a < 6; ++a) {
      t.equation.push_back(dofs.equation(3 * (a < 3 ? e.start : e.end) + a % 3));
      t.u[a] = value(random);
      t.v[a] = value(random);
    }
  }
  return terms;
}

// Solves as a dense LU of the same K_ff does; returns how often the tangent was asked for again.
int expect_solves(const Setup& s, BlockMatrix a, const std::vector<RankOne>& terms) {
  const Eigen::MatrixXd K = dense_tangent(*s.dofs, a, terms);
  const BlockMatrix original = a;
  int refills = 0;
  const auto refill = [&](BlockMatrix& m) {
    ++refills;
    m.value = original.value;
  };
  tsm::solver::LinearSolver solver;
  solver.analyze(*s.dofs, a);
  EXPECT_TRUE(solver.factorize(a, terms, refill));
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(K.rows(), -1.0, 2.0);
  const Eigen::VectorXd expected = K.fullPivLu().solve(b);
  EXPECT_LT((solver.solve(b) - expected).norm(), 1e-10 * expected.norm());
  Eigen::VectorXd x = b;
  solver.solve_in_place(x);
  EXPECT_LT((x - expected).norm(), 1e-10 * expected.norm());
  // The same in one call, the forward substitution riding along the factorisation.
  BlockMatrix fresh = original;
  tsm::solver::LinearSolver fused;
  fused.analyze(*s.dofs, fresh);
  Eigen::VectorXd y = b;
  EXPECT_TRUE(fused.factorize_and_solve(fresh, terms, y, refill));
  EXPECT_LT((y - expected).norm(), 1e-10 * expected.norm());
  return refills;
}

TEST(LinearSolver, BlockLDLTAlone) {
  const auto s = setup(1, 12.0);
  expect_solves(*s, s->tangent, {});
}

TEST(LinearSolver, BlockLDLTWithConstrainedDofsInsideABlock) {
  // Pin and roller: their blocks keep the rotation (and u) only, the solver pads the vectors.
  const auto s = setup(5, 12.0, "pinned");
  expect_solves(*s, s->tangent, {});
}

TEST(LinearSolver, FewSlidingTermsByWoodbury) {
  const auto s = setup(2, 12.0);
  expect_solves(*s, s->tangent, rank_ones(*s->dofs, 3, 7));
}

TEST(LinearSolver, ManySlidingTermsOnTheirElementsNodesByTheBlockLU) {
  const auto s = setup(3, 12.0);
  EXPECT_EQ(expect_solves(*s, s->tangent, element_rank_ones(s->model, *s->dofs, 40, 8)), 0);
  const auto pinned = setup(6, 12.0, "pinned");  // and with constrained dofs inside a block
  EXPECT_EQ(expect_solves(*pinned, pinned->tangent, element_rank_ones(pinned->model, *pinned->dofs, 40, 9)), 0);
}

TEST(LinearSolver, ABlockLUPivotThatNeedsPivotingFallsBackToSparseLUOnTheTangentAskedForAgain) {
  // The first block eliminated is singular in its u dof alone (no pivot there without
  // pivoting), the whole regular through its couplings; 40 terms on elements away from it.
  const auto s = setup(7, 12.0);
  BlockMatrix a = s->tangent;
  Block& first = a.value[a.column[0]];
  first.row(0).setZero();
  first.col(0).setZero();
  const int held = s->dofs->block_node(0);
  std::vector<RankOne> terms;
  for (const RankOne& t : element_rank_ones(s->model, *s->dofs, 200, 10)) {
    bool touches = false;
    for (const int eq : t.equation) touches = touches || (eq >= 0 && s->dofs->dof(eq) / 3 == held);
    if (!touches && terms.size() < 40) terms.push_back(t);
  }
  ASSERT_EQ(terms.size(), 40u);
  EXPECT_EQ(expect_solves(*s, a, terms), 2);  // factorize, factorize_and_solve
}

TEST(LinearSolver, OneSolverGoesFromTheBlockLUToWoodburyToTheLDLTAndOnToANewPattern) {
  const auto s = setup(8, 12.0);
  const auto pinned = setup(9, 12.0, "pinned");
  tsm::solver::LinearSolver solver;
  const auto solves = [&](const ::Setup& setup, const std::vector<RankOne>& terms, bool symmetric) {
    BlockMatrix a = setup.tangent;
    const Eigen::MatrixXd K = dense_tangent(*setup.dofs, a, terms);
    ASSERT_TRUE(solver.factorize(a, terms));
    const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(K.rows(), -1.0, 2.0);
    const Eigen::VectorXd expected = K.fullPivLu().solve(b);
    EXPECT_LT((solver.solve(b) - expected).norm(), 1e-10 * expected.norm()) << terms.size() << " terms";
    EXPECT_EQ(solver.inertia().has_value(), symmetric) << terms.size() << " terms";
  };
  solver.analyze(*s->dofs, s->tangent);
  solves(*s, element_rank_ones(s->model, *s->dofs, 40, 11), false);
  solves(*s, element_rank_ones(s->model, *s->dofs, 3, 12), true);
  solves(*s, {}, true);
  solves(*s, element_rank_ones(s->model, *s->dofs, 50, 13), false);
  solver.analyze(*pinned->dofs, pinned->tangent);  // another pattern: the block LU analysed anew
  solves(*pinned, element_rank_ones(pinned->model, *pinned->dofs, 40, 14), false);
}

TEST(LinearSolver, ManySlidingTermsOutsideThePatternBySparseLUOnTheTangentAskedForAgain) {
  const auto s = setup(3, 12.0);
  EXPECT_EQ(expect_solves(*s, s->tangent, rank_ones(*s->dofs, 40, 8)), 2);  // factorize, factorize_and_solve
}

TEST(LinearSolver, SingularSymmetricPartFallsBackToSparseLUWithTheTangentIntact) {
  // A block-diagonal tangent whose last block is singular in its u direction: the in-place LDLᵀ
  // fails on that pivot; the sliding term u vᵀ on that dof makes K_ff regular.
  const auto s = setup(4, 12.0);
  BlockMatrix a = s->tangent;
  int last = -1;
  for (int c = 0; c < a.size; ++c)
    for (int p = a.column[c]; p < a.column[c + 1]; ++p) {
      a.value[p] = a.row[p] == c ? Block(2.0 * Block::Identity()) : Block(Block::Zero());  // D⁻¹ differs from D
      if (a.row[p] == c) last = p;
    }
  a.value[last](0, 0) = 0.0;
  const int block = a.size - 1;
  RankOne t{{s->dofs->equation(3 * s->dofs->block_node(block))}, Eigen::VectorXd::Constant(1, 2.0),
            Eigen::VectorXd::Constant(1, 1.5)};
  ASSERT_GE(t.equation[0], 0);
  const Eigen::MatrixXd K = dense_tangent(*s->dofs, a, {t});
  const BlockMatrix original = a;
  tsm::solver::LinearSolver solver;
  solver.analyze(*s->dofs, a);
  int refills = 0;
  const auto refill = [&](BlockMatrix& m) {
    ++refills;
    m.value = original.value;
  };
  ASSERT_TRUE(solver.factorize(a, {t}, refill));
  EXPECT_EQ(refills, 1);
  for (size_t p = 0; p < a.value.size(); ++p) ASSERT_EQ(a.value[p], original.value[p]);  // SparseLU reads, never writes
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(K.rows(), 1.0, 3.0);
  EXPECT_LT((solver.solve(b) - K.fullPivLu().solve(b)).norm(), 1e-12 * b.norm());
  // The same through factorize_and_solve.
  BlockMatrix again = original;
  tsm::solver::LinearSolver fused;
  fused.analyze(*s->dofs, again);
  Eigen::VectorXd x = b;
  ASSERT_TRUE(fused.factorize_and_solve(again, {t}, x, refill));
  EXPECT_EQ(refills, 2);
  EXPECT_LT((x - K.fullPivLu().solve(b)).norm(), 1e-12 * b.norm());
  // Without the sliding term the same tangent is reported singular.
  BlockMatrix alone = original;
  tsm::solver::LinearSolver plain;
  plain.analyze(*s->dofs, alone);
  EXPECT_FALSE(plain.factorize(alone, {}));
}

}  // namespace
