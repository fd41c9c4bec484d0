// Contacts landing together (contact/landing.hpp), end to end: a flexible beam pressed onto a
// stiff one, whose first iterate would carry it metres through the lower beam, lands in each of
// its steps without a cutback and ends where smaller steps end.
#include <gtest/gtest.h>

#include "support/contact_models.hpp"

namespace test_landing_end_to_end {
namespace {

using namespace tsm::test;
using tsm::solver::RunResult;

TEST(ContactLanding, TwoHundredContactNodesPressedInTenStepsLandWithoutCutbackAndEndAsInForty) {
  // 201 contact nodes drawn 1 cm above the lower beam's 5-cm gap, 2 kN/m: at λ = 0.1 the upper
  // beam alone would sag 1.3 m, and the first iterate ran it through the lower beam; the first
  // step was cut back three times (to λ = 0.025) and the run took 13 steps. The whole path is
  // elastic and frictionless: 40 steps end in the same state.
  tsm::Model model;
  const RunResult ten = run(pressed_beams(-2000.0, 10), model);
  ASSERT_EQ(ten.status, tsm::solver::Status::converged) << ten.message;
  ASSERT_EQ(ten.steps.size(), 10u);
  for (const tsm::solver::StepRecord& s : ten.steps) EXPECT_EQ(s.cutbacks, 0) << "step " << s.step;
  expect_equilibrium(model, ten.steps.back());
  const RunResult forty = run(pressed_beams(-2000.0, 40), model);
  ASSERT_EQ(forty.status, tsm::solver::Status::converged) << forty.message;
  const Eigen::VectorXd& a = ten.steps.back().displacements;
  const Eigen::VectorXd& b = forty.steps.back().displacements;
  EXPECT_LT((a - b).lpNorm<Eigen::Infinity>(), 1e-9 * a.lpNorm<Eigen::Infinity>());
}

}  // namespace
}  // namespace test_landing_end_to_end
