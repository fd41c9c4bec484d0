// A staged analysis ("stages"; issue 29): each stage's loads and prescribed displacements scaled
// by its own λ, what earlier stages applied held at their final level. Checked against exact
// values: an elastic conservative cantilever ends where one stage takes it (path independence);
// follower loads held dead end where one stage takes them; a column's axial load held while a
// lateral load is added bends it as the beam-column formula says; a roller pressed a fixed depth
// into a cantilever and then slid along it, through element ends, pushes with 3EIδ/a³; a stage
// that fails keeps the steps before it and says which stage it was.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "support/contact_models.hpp"
#include "support/models.hpp"

namespace test_stages {
namespace {

using namespace tsm::test;

json load_control(int steps) { return {{"type", "load"}, {"steps", steps}}; }

/// The largest difference between two states' displacements, over the largest displacement.
double relative_difference(const tsm::solver::StepRecord& a, const tsm::solver::StepRecord& b) {
  return (a.displacements - b.displacements).lpNorm<Eigen::Infinity>() / b.displacements.lpNorm<Eigen::Infinity>();
}

/// A cantilever of 10 EB elements (EI 1, L 1) clamped at node 1, converged to 1e-12.
json cantilever() {
  json m = beam_model({});
  m["supports"] = json::array({{{"node", 1}, {"type", "fixed"}}});
  m["analysis"] = {{"tolerance", 1e-12}};
  return m;
}

TEST(Stages, AnElasticCantileverEndsWhereOneStageTakesIt) {
  // A tip force (P L²/EI = 1.5: the tip turns ~0.6 rad) in stage 1, a tip moment in stage 2.
  json staged = cantilever();
  staged["stages"] = json::array({{{"name", "force"}, {"loads", json::array({{{"node", 2}, {"fy", 1.5}}})}, {"control", load_control(5)}},
                                  {{"name", "moment"}, {"loads", json::array({{{"node", 2}, {"mz", 0.8}}})}, {"control", load_control(5)}}});
  json single = cantilever();
  single["loads"] = json::array({{{"node", 2}, {"fy", 1.5}, {"mz", 0.8}}});
  single["analysis"]["control"] = load_control(10);
  tsm::Model staged_model, single_model;
  const tsm::solver::RunResult a = run(staged, staged_model), b = run(single, single_model);
  ASSERT_EQ(a.status, tsm::solver::Status::converged) << a.message;
  ASSERT_EQ(b.status, tsm::solver::Status::converged) << b.message;
  ASSERT_EQ(a.steps.size(), 10u);
  EXPECT_EQ(a.steps[4].stage, 0);
  EXPECT_EQ(a.steps[5].stage, 1);
  EXPECT_EQ(a.steps[5].step, 6);  // numbered through
  EXPECT_EQ(a.steps.back().load_factor, 1.0);  // the stage's own λ
  const double difference = relative_difference(a.steps.back(), b.steps.back());
  std::printf("[figure] staged against one stage: %.2e of the largest displacement\n", difference);
  EXPECT_LT(difference, 1e-9);
  // The reactions hold both stages' loads: the moment at the clamp is P x_tip + M.
  const double tip_x = 1.0 + node_displacement(staged_model, a.steps.back(), 2)[0];
  EXPECT_NEAR(a.steps.back().reactions[2], -(1.5 * tip_x + 0.8), 1e-9);
  ASSERT_EQ(a.stages.size(), 2u);
  EXPECT_EQ(a.stages[0].last_step, 5);
  EXPECT_EQ(a.stages[1].last_step, 10);
}

TEST(Stages, FollowerLoadsHeldByALaterStageStillTurn) {
  // Stage 1: a pressure on the member and a follower tip force; stage 2: another follower force
  // at the tip. Both follower loads of stage 1 are held (dead) and keep turning: the end state is
  // the one-stage equilibrium under the sum (unique for these loads).
  json staged = cantilever();
  staged["members"][0]["load"] = {{"pressure", 0.6}};
  staged["stages"] = json::array({{{"loads", json::array({{{"node", 2}, {"fy", 1.0}, {"follower", true}}})}, {"control", load_control(4)}},
                                  {{"loads", json::array({{{"node", 2}, {"fx", -0.5}, {"follower", true}}})}, {"control", load_control(4)}}});
  json single = cantilever();
  single["members"][0]["load"] = {{"pressure", 0.6}};
  single["loads"] = json::array({{{"node", 2}, {"fx", -0.5}, {"fy", 1.0}, {"follower", true}}});
  single["analysis"]["control"] = load_control(8);
  tsm::Model staged_model, single_model;
  const tsm::solver::RunResult a = run(staged, staged_model), b = run(single, single_model);
  ASSERT_EQ(a.status, tsm::solver::Status::converged) << a.message;
  ASSERT_EQ(b.status, tsm::solver::Status::converged) << b.message;
  const double difference = relative_difference(a.steps.back(), b.steps.back());
  std::printf("[figure] follower loads held: %.2e of the largest displacement; tip turned %.3f rad\n", difference,
              node_displacement(staged_model, a.steps.back(), 2)[2]);
  EXPECT_LT(difference, 1e-9);
  EXPECT_GT(std::abs(node_displacement(staged_model, a.steps.back(), 2)[2]), 0.3);  // the loads did turn
  // Newton's tangent holds the dead follower loads' stiffness: stage 2 converges as the single run does.
  for (const auto& step : a.steps) EXPECT_LE(step.iterations, 8) << "step " << step.step;
}

TEST(Stages, AColumnsAxialLoadIsHeldWhileALateralLoadBendsIt) {
  // A cantilever column (EI 1, L 1, 40 elements) under P = 0.5 P_cr (P_cr = π²/4) in stage 1,
  // then a small lateral tip load H: the beam-column tip deflection δ = H (tan kL − kL) / (P k),
  // k = √(P/EI) — 2.06 times H L³/3EI, what it would be without P.
  const double P = 0.5 * M_PI * M_PI / 4.0, H = 1e-4, k = std::sqrt(P);
  json m = cantilever();
  m["nodes"][1] = {{"id", 2}, {"x", 0.0}, {"y", 1.0}};
  m["members"][0]["divisions"] = 40;
  m["analysis"]["tolerance"] = 1e-10;
  m["stages"] = json::array({{{"name", "axial"}, {"loads", json::array({{{"node", 2}, {"fy", -P}}})}, {"control", load_control(2)}},
                             {{"name", "lateral"}, {"loads", json::array({{{"node", 2}, {"fx", H}}})}, {"control", load_control(2)}}});
  tsm::Model model;
  const tsm::solver::RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  EXPECT_NEAR(node_displacement(model, r.steps[1], 2)[0], 0.0, 1e-14);  // stage 1: straight
  const double exact = H * (std::tan(k) - k) / (P * k), tip = node_displacement(model, r.steps.back(), 2)[0];
  std::printf("[figure] beam-column tip deflection %.6e against %.6e: %.2e off (H L^3/3EI: %.3e)\n", tip, exact,
              tip / exact - 1.0, H / 3.0);
  EXPECT_NEAR(tip / exact, 1.0, 1e-3);  // the elements' lumped P-δ: O(h²)
  // The clamp holds both stages' loads: P and H, and the moment H L + P δ.
  EXPECT_NEAR(r.steps.back().reactions[1], P, 1e-10 * P);  // to the run's tolerance
  EXPECT_NEAR(r.steps.back().reactions[0], -H, 1e-10 * P);
  EXPECT_NEAR(r.steps.back().reactions[2], H * 1.0 + P * tip, 1e-3 * H);
}

TEST(Stages, ARollerPressedIntoACantileverThenSlidAlongItPushesAsTheClosedFormSays) {
  // Stage 1 presses a rigid roller (node 100) δ = 1e-3 into a cantilever (EI 1, L 1, 10
  // elements) at a = 0.45; stage 2 moves it 0.4 along x, its depth held, through the element
  // ends at 0.5 … 0.8. A point load at a deflects the cantilever there by F a³/3EI: F = 3EIδ/a³.
  const double depth = 1e-3;
  json m = cantilever();
  m["analysis"]["tolerance"] = 1e-10;
  m["nodes"].push_back({{"id", 100}, {"x", 0.45}, {"y", 0.0}});
  m["contacts"] = json::array({{{"node", 100}, {"members", "all"}}});
  m["stages"] = json::array({{{"name", "press"}, {"prescribed", json::array({{{"node", 100}, {"ux", 0.0}, {"uy", -depth}}})}, {"control", load_control(4)}},
                             {{"name", "slide"}, {"prescribed", json::array({{{"node", 100}, {"ux", 0.4}, {"increment", true}}})}, {"control", load_control(16)}}});
  tsm::Model model;
  const tsm::solver::RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  ASSERT_EQ(r.steps.size(), 20u);
  double worst = 0.0;
  int elements_visited = 0, last_element = -1;
  for (const tsm::solver::StepRecord& step : r.steps) {
    const Eigen::Vector3d roller = node_displacement(model, step, 100);
    EXPECT_NEAR(roller[1], -depth * (step.stage == 0 ? step.load_factor : 1.0), 1e-15) << "step " << step.step;
    const double a = 0.45 + roller[0], exact = 3.0 * (-roller[1]) / (a * a * a);
    const tsm::solver::ContactPoint& c = contact_of(step);
    ASSERT_GE(c.element, 0) << "step " << step.step;
    worst = std::max(worst, std::abs(c.force / exact - 1.0));
    if (c.element != last_element) ++elements_visited, last_element = c.element;
    expect_equilibrium(model, step);
  }
  std::printf("[figure] roller force against 3EI delta/a^3 over 20 steps: %.2e at worst; %d elements visited\n", worst,
              elements_visited);
  EXPECT_LT(worst, 2e-3);  // the beam's shortening and turn (δ/a ~ 2e-3)
  EXPECT_EQ(elements_visited, 5);  // 0.45 → 0.85 crosses 0.5, 0.6, 0.7, 0.8
  EXPECT_NEAR(node_displacement(model, r.steps.back(), 100)[0], 0.4, 1e-15);
}

TEST(Stages, AContactLeftOutOfAStageLetsGoAndComesBackWhereItsNodeThenIs) {
  // Stage 1 presses a roller δ into a cantilever (EI 1) at a = 0.45; stage 2 leaves the contact
  // out ("contacts": []) and moves the roller on down through where the beam was: the beam
  // springs back straight. Stage 3 brings the contact back and lifts the roller 3δ: it meets the
  // beam from below and lifts it δ, pushing 3EIδ/a³ up.
  const double depth = 1e-3, a = 0.45;
  json m = cantilever();
  m["analysis"]["tolerance"] = 1e-10;
  m["nodes"].push_back({{"id", 100}, {"x", a}, {"y", 0.0}});
  m["contacts"] = json::array({{{"node", 100}, {"members", "all"}}});
  m["stages"] = json::array(
      {{{"name", "press"}, {"prescribed", json::array({{{"node", 100}, {"ux", 0.0}, {"uy", -depth}}})}, {"control", load_control(2)}},
       {{"name", "away"}, {"contacts", json::array()}, {"prescribed", json::array({{{"node", 100}, {"uy", -2.0 * depth}}})}, {"control", load_control(2)}},
       {{"name", "lift"}, {"contacts", {0}}, {"prescribed", json::array({{{"node", 100}, {"uy", 3.0 * depth}, {"increment", true}}})},
        {"control", load_control(6)}}});
  tsm::Model model;
  const tsm::solver::RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  ASSERT_EQ(r.steps.size(), 10u);
  EXPECT_GE(contact_of(r.steps[1]).element, 0);  // pressed
  EXPECT_NEAR(contact_of(r.steps[1]).force, 3.0 * depth / (a * a * a), 1e-3 * 3.0 * depth / (a * a * a));
  for (int k : {2, 3}) EXPECT_LT(contact_of(r.steps[k]).element, 0) << "step " << k + 1;  // left out
  EXPECT_LT(node_displacement(model, r.steps[3], 2).head<2>().norm(), 1e-12);  // sprung back straight
  const tsm::solver::StepRecord& last = r.steps.back();
  ASSERT_GE(contact_of(last).element, 0);
  EXPECT_NEAR(node_displacement(model, last, 100)[1], depth, 1e-15);
  EXPECT_NEAR(contact_of(last).force, 3.0 * depth / (a * a * a), 2e-3 * 3.0 * depth / (a * a * a));
  EXPECT_GT(node_displacement(model, last, 2)[1], 0.0);  // lifted from below
  json bad = m;
  bad["stages"][1]["contacts"] = {1};
  EXPECT_NE(refusal(bad).find("stages[1].contacts[0]: no contacts entry 1"), std::string::npos) << refusal(bad);
}

TEST(Stages, AStageThatFailsKeepsTheStepsBeforeItAndSaysWhichStage) {
  // Stage 2's arc-length control runs out of steps long before its λ = 1 (status step-limit).
  json m = cantilever();
  m["stages"] = json::array({{{"name", "small"}, {"loads", json::array({{{"node", 2}, {"fy", 0.1}}})}, {"control", load_control(2)}},
                             {{"name", "huge"},
                              {"loads", json::array({{{"node", 2}, {"fy", 1e4}}})},
                              {"control", {{"type", "arc-length"}, {"initial_increment", 1e-3}, {"max_steps", 2}, {"until", {{"load_factor", 1.0}}}}}}});
  tsm::Model model;
  const tsm::solver::RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::step_limit);
  EXPECT_EQ(r.message.rfind("In stage 2 (\"huge\"): ", 0), 0u) << r.message;
  ASSERT_EQ(r.steps.size(), 4u);
  EXPECT_TRUE(r.steps[1].converged);
  EXPECT_EQ(r.steps[1].stage, 0);
  EXPECT_EQ(r.steps.back().stage, 1);
  EXPECT_EQ(r.steps.back().step, 4);
  ASSERT_EQ(r.stages.size(), 2u);
  EXPECT_EQ(r.stages[0].last_step, 2);
  EXPECT_EQ(r.stages[0].status, tsm::solver::Status::converged);
  EXPECT_EQ(r.stages[1].last_step, 4);
  EXPECT_EQ(r.stages[1].status, tsm::solver::Status::step_limit);
}

TEST(Stages, ADisplacementControlThatStartsAtItsTargetRunsNoStepAndSaysSo) {
  // Stage 1 pulls the tip along the axis (uy stays 0); stage 2 asks uy to reach 0 — where it is;
  // stage 3 goes on. A later stage's target may be 0 (the reader takes it: it starts elsewhere).
  json m = cantilever();
  m["stages"] = json::array({{{"loads", json::array({{{"node", 2}, {"fx", 0.1}}})}},
                             {{"name", "idle"}, {"loads", json::array({{{"node", 2}, {"fy", 0.1}}})},
                              {"control", {{"type", "displacement"}, {"node", 2}, {"dof", "uy"}, {"target", 0.0}}}},
                             {{"loads", json::array({{{"node", 2}, {"fy", 0.1}}})}, {"control", load_control(2)}}});
  tsm::Model model;
  const tsm::solver::RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  ASSERT_EQ(r.steps.size(), 3u);
  EXPECT_EQ(r.steps[1].step, 2);
  EXPECT_EQ(r.steps[1].stage, 2);
  ASSERT_EQ(r.notes.size(), 1u);
  EXPECT_EQ(r.notes[0], "In stage 2 (\"idle\"): its displacement control starts at its target (uy of node 2 = 0): nothing to drive, no step run");
  EXPECT_EQ(r.stages[1].last_step, 0);
  // Stage 3 bends the cantilever under the tension stage 1 left: v = P/T (L − tanh(kL)/k), k = √(T/EI)
  // (stage 2's load never applied: it ran no step).
  const double k = std::sqrt(0.1), exact = (0.1 / 0.1) * (1.0 - std::tanh(k) / k);
  EXPECT_NEAR(node_displacement(model, r.steps.back(), 2)[1] / exact, 1.0, 2e-3);
}

TEST(Stages, TheReaderRefusesWhatAStagedModelCannotMean) {
  json m = cantilever();
  m["stages"] = json::array({{{"loads", json::array({{{"node", 2}, {"fy", 1.0}}})}}});
  json top_loads = m;
  top_loads["loads"] = json::array({{{"node", 2}, {"fy", 1.0}}});
  EXPECT_NE(refusal(top_loads).find("loads: with \"stages\""), std::string::npos) << refusal(top_loads);
  json top_control = m;
  top_control["analysis"]["control"] = load_control(2);
  EXPECT_NE(refusal(top_control).find("analysis.control: with \"stages\""), std::string::npos) << refusal(top_control);
  json unknown_node = m;
  unknown_node["stages"][0]["loads"][0]["node"] = 99;
  EXPECT_NE(refusal(unknown_node).find("stages[0].loads[0].node"), std::string::npos) << refusal(unknown_node);
  json typo = m;
  typo["stages"][0]["contol"] = load_control(2);
  EXPECT_NE(refusal(typo).find("stages[0]"), std::string::npos) << refusal(typo);
  json prescribed_then_controlled = m;  // a dof an earlier stage prescribed is held: no control moves it
  prescribed_then_controlled["stages"][0]["prescribed"] = json::array({{{"node", 2}, {"uy", 0.1}}});
  prescribed_then_controlled["stages"].push_back(
      {{"control", {{"type", "displacement"}, {"node", 2}, {"dof", "uy"}, {"target", 0.2}}}});
  EXPECT_NE(refusal(prescribed_then_controlled).find("stages[1].control.dof"), std::string::npos)
      << refusal(prescribed_then_controlled);
  json empty = m;
  empty["stages"] = json::array();
  EXPECT_NE(refusal(empty).find("stages: give 1 to 1000 stages"), std::string::npos) << refusal(empty);
  json top_increment = m;  // "increment" belongs to a stage's prescribed displacements
  top_increment.erase("stages");
  top_increment["prescribed"] = json::array({{{"node", 2}, {"uy", 0.1}, {"increment", true}}});
  EXPECT_NE(refusal(top_increment).find("prescribed[0]"), std::string::npos) << refusal(top_increment);
}

TEST(Stages, DisplacementControlInALaterStageRunsFromWhereTheDofStands) {
  // Stage 1 pulls the tip up by a force; stage 2 drives it under displacement control to an
  // absolute height. The stage's λ is then the load factor of its own tip force that holds it.
  json m = cantilever();
  m["stages"] = json::array({{{"loads", json::array({{{"node", 2}, {"fy", 0.3}}})}, {"control", load_control(2)}},
                             {{"loads", json::array({{{"node", 2}, {"fy", 0.3}}})},
                              {"control", {{"type", "displacement"}, {"node", 2}, {"dof", "uy"}, {"target", 0.19}, {"steps", 3}}}}});
  tsm::Model model;
  const tsm::solver::RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  const double start = node_displacement(model, r.steps[1], 2)[1];
  EXPECT_NEAR(start, 0.1, 0.01);  // P L³/3EI = 0.1, shortened a little by the bending
  for (int k = 2; k < 5; ++k)
    EXPECT_NEAR(node_displacement(model, r.steps[k], 2)[1], start + (0.19 - start) * (k - 1) / 3.0, 1e-12) << "step " << k + 1;
  // A second stage's tip force 0.3 λ on top of the held 0.3: the same cantilever as one load
  // (0.3 + 0.3 λ) reaching 0.19 — about 0.3 × 0.9, λ ≈ 0.9 from the linear estimate.
  EXPECT_NEAR(r.steps.back().load_factor, 0.9, 0.1);
  EXPECT_NEAR(r.steps.back().reactions[1], -0.3 * (1.0 + r.steps.back().load_factor), 1e-9);
}

}  // namespace

}  // namespace test_stages
