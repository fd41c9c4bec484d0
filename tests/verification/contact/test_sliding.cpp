// A contact point sliding along the beam through element ends and across a joint between two
// members, every step converging, and over a mesh of many short elements in few iterates.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "support/contact_models.hpp"

namespace {

using namespace tsm::test;
using tsm::solver::RunResult;
using tsm::solver::StepRecord;

// ---- Sliding across element ends ----

class AcrossElementEnds : public ::testing::TestWithParam<PushCase> {};

TEST_P(AcrossElementEnds, EveryStepConvergesAndThePointMovesMonotonically) {
  // The pusher presses the beam down slightly while travelling from x = 0.2 to x = 0.8 along it:
  // the contact point crosses 12 element ends of a 20-element mesh.
  BeamSpec b;
  b.divisions = 20;
  b.A = 1e5;
  b.element = GetParam().element;
  tsm::Model model;
  json m = pusher_model(b, 0.2, 0.0, 0.6, 0.05, 30);
  m["contacts"][0]["frame"] = GetParam().frame;
  const RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  double previous_position = -1.0;
  int previous_element = -1, crossed = 0;
  for (const StepRecord& s : r.steps) {
    ASSERT_TRUE(s.converged);
    EXPECT_EQ(s.cutbacks, 0) << "step " << s.step;
    const tsm::solver::ContactPoint& c = contact_of(s);
    ASSERT_GE(c.element, 0) << "step " << s.step;
    EXPECT_GE(c.element, previous_element);
    crossed += previous_element >= 0 ? c.element - previous_element : 0;
    const double position = contact_arc_length(c, 1.0, 20);
    EXPECT_GT(position, previous_position) << "step " << s.step;
    EXPECT_GT(c.force, 0.0);
    previous_position = position;
    previous_element = c.element;
    expect_equilibrium(model, s);
  }
  EXPECT_GE(crossed, 10);
}

INSTANTIATE_TEST_SUITE_P(Formulations, AcrossElementEnds,
                         ::testing::Values(PushCase{"euler-bernoulli", "chord"}, PushCase{"timoshenko", "chord"},
                                           PushCase{"euler-bernoulli", "cantilever"}, PushCase{"timoshenko", "cantilever"}));

TEST(AcrossMembers, ThePointPassesAJointBetweenTwoMembers) {
  // The beam is two members meeting at x = 0.5 with a 3° kink (the second one drawn from its far
  // end, so its chord and normal point the other way): the contact crosses the joint.
  BeamSpec b;
  b.divisions = 10;
  b.A = 1e5;
  json m = pusher_model(b, 0.2, 0.0, 0.6, 0.05, 30);
  const double kink = 0.5 * std::tan(3.0 * std::numbers::pi / 180.0);
  m["nodes"].push_back({{"id", 3}, {"x", 0.5}, {"y", 0.0}});
  m["nodes"][1]["y"] = kink;
  m["members"] = json::array({{{"from", 1}, {"to", 3}, {"divisions", 10}, {"material", "m"}, {"section", "s"}},
                              {{"from", 2}, {"to", 3}, {"divisions", 10}, {"material", "m"}, {"section", "s"}}});
  tsm::Model model;
  const RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  bool on_first = false, on_second = false;
  for (const StepRecord& s : r.steps) {
    const tsm::solver::ContactPoint& c = contact_of(s);
    ASSERT_GE(c.element, 0) << "step " << s.step;
    EXPECT_GT(c.force, 0.0) << "step " << s.step;
    (model.elements[c.element].member == 0 ? on_first : on_second) = true;
    if (model.elements[c.element].member == 1) {
      EXPECT_TRUE(on_first);
    }
    expect_equilibrium(model, s);
  }
  EXPECT_TRUE(on_first && on_second);
}

// ---- Many short elements ----

TEST(FineMesh, APushSlidingOverManyShortElementsTakesFewIteratesPerStep) {
  // The contact-push example on a mesh of 4.5 mm Timoshenko elements: the point slides over
  // ~30 elements a step, and with Ψ = EI/(G A_s) ~ 1500 l0² the contact element is far stiffer
  // than the beam around it. The sliding terms join the solve only near the solution
  // (newton.cpp, sliding_terms_below): with them in every solve the point hopped between
  // elements, 8–21 iterates a step and a cutback. The answer is that of the quasi-Newton variant
  // (sliding terms never used, converging by another path).
  BeamSpec b{.L = 9.0, .E = 2.05e11, .G = 7.9e10, .A = 1e-2, .I = 1e-4, .shear_area = 8.3e-3, .divisions = 2000,
             .element = "timoshenko"};
  json m = pusher_model(b, 4.05, 0.0, 0.0, 1.0, 10);
  tsm::Model model, quasi_model;
  const RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  ASSERT_EQ(r.steps.size(), 10u);
  int total = 0;
  for (const StepRecord& s : r.steps) {
    EXPECT_EQ(s.cutbacks, 0) << "step " << s.step;
    EXPECT_LE(s.iterations, 12) << "step " << s.step;
    total += s.iterations;
    expect_equilibrium(model, s);
  }
  std::printf("[figure] 2000-element push: %d iterates in 10 steps\n", total);
  EXPECT_LE(total, 80);
  m["contacts"][0]["sliding_tangent"] = false;
  const RunResult quasi = run(m, quasi_model);
  ASSERT_EQ(quasi.status, tsm::solver::Status::converged) << quasi.message;
  const tsm::solver::ContactPoint &c = contact_of(r.steps.back()), &q = contact_of(quasi.steps.back());
  EXPECT_NEAR(contact_arc_length(c, 9.0, 2000), contact_arc_length(q, 9.0, 2000), 1e-9);
  EXPECT_NEAR(c.force, q.force, 1e-6 * q.force);
  EXPECT_GT(contact_arc_length(c, 9.0, 2000) - 4.05, 0.1);  // slid over more than 20 elements
}

}  // namespace
