// Newton on a problem it knows only through solver/problem.hpp: a one-dof nonlinear spring
// (support/toy_problem.hpp), whose equilibria are known in closed form.
#include <gtest/gtest.h>

#include <cmath>

#include "support/toy_problem.hpp"
#include "tsmframe/solver/newton.hpp"

namespace {

using tsm::solver::NewtonOutcome;
using tsm::solver::NewtonSolver;
using tsm::solver::PathConstraint;
using tsm::solver::State;
using tsm::solver::Status;
using Reason = tsm::solver::StepFailure::Reason;

/// The real root of k u + c u³ = λ (c > 0: one), by Cardano: u³ + p u − q = 0, p = k/c, q = λ/c.
double hardening_root(double k, double c, double lambda) {
  const double p = k / c, q = lambda / c, r = std::sqrt(q * q / 4.0 + p * p * p / 27.0);
  return std::cbrt(q / 2.0 + r) + std::cbrt(q / 2.0 - r);
}

TEST(Newton, LoadControlFindsTheSpringsEquilibriumInOneStep) {
  tsm::test::ToyProblem spring(2.0, 5.0);
  NewtonSolver newton(spring, {1e-12, 50});
  State state = tsm::test::ToyProblem::start();
  newton.reset(state);
  PathConstraint load;
  load.load_increment = 3.0;
  const NewtonOutcome out = newton.step(load, state);
  ASSERT_EQ(out.status, Status::converged);
  EXPECT_DOUBLE_EQ(state.load_factor, 3.0);
  EXPECT_NEAR(state.displacements[0], hardening_root(2.0, 5.0, 3.0), 1e-12);
  // Quadratic convergence: near the root each residual is about the square of the one before.
  const std::vector<double>& r = out.residual_norms;
  ASSERT_GE(r.size(), 4u);
  for (size_t i = 1; i + 1 < r.size(); ++i)
    if (r[i] < 1e-2 && r[i + 1] > 1e-14) EXPECT_LT(r[i + 1], 10.0 * r[i] * r[i]) << "iterate " << i + 1;
}

TEST(Newton, IteratesAreFarUntilTheResidualFirstFallsBelowOnePercentAndNearFromThenOn) {
  // A stiff cubic spring loaded far beyond its linear range: several iterates above 10⁻²
  // (Problem::evaluate's far, where a structure may evaluate a simpler model), then near for
  // the rest of the step, whatever the residual does after.
  tsm::test::ToyProblem spring(1.0, 1e3);
  NewtonSolver newton(spring, {1e-12, 50});
  State state = tsm::test::ToyProblem::start();
  newton.reset(state);
  PathConstraint load;
  load.load_increment = 1e3;
  const NewtonOutcome out = newton.step(load, state);
  ASSERT_EQ(out.status, Status::converged);
  const std::vector<tsm::solver::Proximity>& said = spring.proximities();
  ASSERT_EQ(said.size(), static_cast<size_t>(out.iterations) + 1);  // the reset's, then each iterate's
  EXPECT_EQ(said.front(), tsm::solver::Proximity::near);
  bool been_near = false;
  int far = 0;
  for (int it = 1; it <= out.iterations; ++it) {
    been_near = been_near || out.residual_norms[it - 1] < 1e-2;  // the residual its correction came from
    EXPECT_EQ(said[it], been_near ? tsm::solver::Proximity::near : tsm::solver::Proximity::far) << "iterate " << it;
    far += said[it] == tsm::solver::Proximity::far;
  }
  EXPECT_GE(far, 3);
  EXPECT_NEAR(state.displacements[0], hardening_root(1.0, 1e3, 1e3), 1e-10);  // Cardano loses digits here
}

TEST(Newton, DisplacementControlPutsTheDofOnItsTargetAndTheLoadOnTheCurve) {
  tsm::test::ToyProblem spring(2.0, -1.0);  // softening: past its maximum at u = √(2/3)
  NewtonSolver newton(spring, {1e-12, 50});
  State state = tsm::test::ToyProblem::start();
  newton.reset(state);
  PathConstraint control;
  control.kind = PathConstraint::Kind::displacement_target;
  control.equation = 0;
  for (const double target : {0.5, 1.0, 1.3}) {  // up to and beyond the limit point
    control.target = target;
    ASSERT_EQ(newton.step(control, state).status, Status::converged) << target;
    EXPECT_NEAR(state.displacements[0], target, 1e-14);
    EXPECT_NEAR(state.load_factor, spring.force(target), 1e-12) << target;
  }
}

TEST(Newton, ArcLengthStepsKeepTheirLengthAndPassTheLimitPoint) {
  tsm::test::ToyProblem spring(2.0, -1.0);
  const double u_max = std::sqrt(2.0 / 3.0), lambda_max = spring.force(u_max);
  NewtonSolver newton(spring, {1e-12, 50});
  State state = tsm::test::ToyProblem::start();
  newton.reset(state);
  PathConstraint arc;
  arc.kind = PathConstraint::Kind::arc_length;
  arc.arc_length = 0.1;  // nothing prescribed: the step moves u by exactly 0.1
  double highest = 0.0;
  for (int step = 0; step < 14; ++step) {
    const double before_u = state.displacements[0], before_lambda = state.load_factor;
    ASSERT_EQ(newton.step(arc, state).status, Status::converged) << step;
    EXPECT_NEAR(std::abs(state.displacements[0] - before_u), 0.1, 1e-12) << step;
    EXPECT_NEAR(state.load_factor, spring.force(state.displacements[0]), 1e-12) << step;
    arc.previous_increment = Eigen::VectorXd::Constant(1, state.displacements[0] - before_u);
    arc.previous_load_increment = state.load_factor - before_lambda;
    highest = std::max(highest, state.load_factor);
  }
  EXPECT_NEAR(state.displacements[0], 1.4, 1e-9);  // on along the path, never doubling back
  EXPECT_LT(state.load_factor, highest);           // the load fell after its maximum
  EXPECT_LE(highest, lambda_max);
  EXPECT_GT(highest, lambda_max - 0.02);           // the step nearest u_max = 0.816 is at 0.8
}

TEST(Newton, ASingularTangentAtTheStartIsAFailureWithItsReason) {
  tsm::test::ToyProblem spring(0.0, 1.0);  // F = u³: no stiffness at u = 0
  NewtonSolver newton(spring, {1e-10, 50});
  State state = tsm::test::ToyProblem::start();
  newton.reset(state);
  PathConstraint load;
  load.load_increment = 1.0;
  const NewtonOutcome out = newton.step(load, state);
  EXPECT_EQ(out.status, Status::singular);
  EXPECT_EQ(out.failure.reason, Reason::singular_tangent);
  EXPECT_EQ(out.failure.iteration, 1);
}

TEST(Newton, TooFewIterationsEndWithTheLastResidualAsAFact) {
  tsm::test::ToyProblem spring(1.0, 10.0);
  NewtonSolver newton(spring, {1e-14, 2});
  State state = tsm::test::ToyProblem::start();
  newton.reset(state);
  PathConstraint load;
  load.load_increment = 50.0;
  const NewtonOutcome out = newton.step(load, state);
  EXPECT_EQ(out.status, Status::max_iterations);
  EXPECT_EQ(out.failure.reason, Reason::max_iterations);
  EXPECT_EQ(out.failure.iteration, 2);
  EXPECT_EQ(out.failure.relative_residual, out.residual_norms.back());
  EXPECT_GT(out.failure.relative_residual, 1e-14);
}

TEST(Newton, DisplacementControlOfADofTheLoadDoesNotMoveFailsAtOnceWhateverTheStepSize) {
  tsm::test::ToyProblem spring(1.0, 0.0);
  spring.set_load(0.0);  // δD_F = K⁻¹ F_dir = 0: no λ moves the dof
  NewtonSolver newton(spring, {1e-12, 50});
  State state = tsm::test::ToyProblem::start();
  newton.reset(state);
  PathConstraint control;
  control.kind = PathConstraint::Kind::displacement_target;
  control.equation = 0;
  control.target = 0.5;
  const NewtonOutcome out = newton.step(control, state);
  EXPECT_EQ(out.status, Status::singular);
  EXPECT_EQ(out.failure.reason, Reason::controlled_dof_immobile);
  EXPECT_EQ(out.failure.iteration, 1);
  EXPECT_TRUE(tsm::solver::independent_of_step_size(out.failure));
}

}  // namespace
