// The convergence test (solver/convergence.hpp), iterate by iterate, on facts made by hand.
#include <gtest/gtest.h>

#include "support/toy_problem.hpp"
#include "tsmframe/solver/convergence.hpp"

namespace {

using tsm::solver::Criterion;
using tsm::solver::ConvergenceTest;
using tsm::solver::IterateFacts;

IterateFacts facts(double relative, double previous, double correction, double largest) {
  IterateFacts f;
  f.relative = relative;
  f.previous = previous;
  f.residual.norms = {relative, 0.0};
  f.residual.scale = {1.0, 1.0};
  f.correction = {correction, 0.0};
  f.largest = {largest, 0.0};
  return f;
}

TEST(Convergence, TheForceCriterionHoldsAtTheTolerance) {
  tsm::test::ToyProblem spring(1.0, 0.0);
  ConvergenceTest test(spring, 1e-8);
  test.begin_step();
  const auto state = tsm::test::ToyProblem::start();
  EXPECT_EQ(test.judge(facts(1e-8, 1e-4, 1e-6, 1.0), state).criterion, Criterion::force);
  EXPECT_EQ(test.judge(facts(2e-8, 1e-4, 1e-6, 1.0), state).criterion, Criterion::none);
}

TEST(Convergence, CorrectionsAtRoundingLevelEndAStepBelowTheFloorCheck) {
  tsm::test::ToyProblem spring(1.0, 0.0);
  ConvergenceTest test(spring, 1e-12);
  test.begin_step();
  const auto state = tsm::test::ToyProblem::start();
  // ‖ΔD‖∞ ≤ 1e-12 · max(size, ‖D‖∞): size 1, D 10 → 1e-11.
  EXPECT_EQ(test.judge(facts(1e-6, 1e-6, 0.9e-11, 10.0), state).criterion, Criterion::round_off);
  EXPECT_EQ(test.judge(facts(1e-6, 1e-6, 1.1e-11, 10.0), state).criterion, Criterion::none);
  // … but not while the contact set changes: the iterate is not an equilibrium of one set.
  IterateFacts changed = facts(1e-6, 1e-6, 0.9e-11, 10.0);
  changed.contacts_changed = true;
  EXPECT_EQ(test.judge(changed, state).criterion, Criterion::none);
}

TEST(Convergence, AResidualNoLongerFallingAtTheRoundingFloorMeansUnresolvableLoads) {
  tsm::test::ToyProblem spring(1.0, 0.0);
  ConvergenceTest test(spring, 1e-12);
  test.begin_step();
  tsm::solver::State state = tsm::test::ToyProblem::start();
  state.displacements[0] = 1.0;  // the floor: ε · k u ≈ 2.2e-16
  // Five iterates that do not halve the best so far, far above the tolerance, with ‖R‖ at the floor.
  IterateFacts f = facts(0.5, 0.5, 1.0, 1.0);
  f.residual.norms = {1e-16, 0.0};
  f.residual.scale = {1e-13, 1e-13};  // the structure carries something: not noise
  tsm::solver::Verdict verdict;
  for (int i = 0; i < 6 && !verdict.loads_unresolvable; ++i) verdict = test.judge(f, state);
  EXPECT_TRUE(verdict.loads_unresolvable);
}

TEST(Convergence, DivergenceIsABlowUpAgainstTheStepsForceLevel) {
  tsm::test::ToyProblem spring(1.0, 0.0);
  ConvergenceTest test(spring, 1e-8);
  test.begin_step();
  EXPECT_DOUBLE_EQ(test.set_step_scale({1.0, 1.0}, {0.5, 0.0}), 0.5);  // iterate 0: the drive against the scale
  IterateFacts f = facts(1.0, 1.0, 1.0, 1.0);
  f.residual.norms = {0.9e12, 0.0};
  EXPECT_FALSE(test.diverged(f, 1.0));
  f.residual.norms = {1.1e12, 0.0};
  EXPECT_TRUE(test.diverged(f, 1.0));
}

}  // namespace
