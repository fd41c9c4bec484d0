// A cable modelled straight: 40 elements of steel wire (A = 1 cm², I next to nothing) pinned at
// both ends 20 m apart, its weight q as a member load, in one load step. The straight start has
// only EI against the load, so Newton's first iterate overshoots by about qL⁴/EI; the cable
// still converges, and where cutback runs out the failure says how to go on.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "support/models.hpp"

namespace {

using namespace tsm::test;

constexpr double span = 20.0, EA = 2.0e11 * 1.0e-4;

json straight_cable(double q) {
  return json{
      {"materials", {{"steel", {{"E", 2.0e11}}}}},
      {"sections", {{"wire", {{"A", 1.0e-4}, {"I", 1.0e-12}}}}},
      {"nodes", json::array({{{"id", 1}, {"x", 0.0}, {"y", 0.0}}, {{"id", 2}, {"x", span}, {"y", 0.0}}})},
      {"members", json::array({{{"from", 1}, {"to", 2}, {"divisions", 40}, {"material", "steel"}, {"section", "wire"},
                                {"load", {{"fy", -q}}}}})},
      {"supports", json::array({{{"node", 1}, {"type", "pinned"}}, {{"node", 2}, {"type", "pinned"}}})},
      {"analysis", {{"control", {{"type", "load"}, {"steps", 1}}}}},
  };
}

TEST(StraightCable, SagsUnderItsWeightAsTheElasticParabolaInOneStep) {
  // A taut cable of small sag f: the parabola's extra length 8f²/3L equals the stretch HL/EA with
  // H = qL²/8f, so f³ = 3qL⁴/(64 EA); here f/L ≈ 0.7 %, where the parabola holds to ~1e-4.
  const double q = 8.0;
  tsm::Model model;
  const auto r = run(straight_cable(q), model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  ASSERT_EQ(r.steps.size(), 1u);
  const double sag = std::cbrt(3.0 * q * std::pow(span, 4) / (64.0 * EA));
  const double H = q * span * span / (8.0 * sag);
  const auto& step = r.steps.back();
  double lowest = 0.0;
  for (int k = 0; k < model.node_count(); ++k) lowest = std::min(lowest, step.displacements[3 * k + 1]);
  EXPECT_NEAR(-lowest, sag, 5e-3 * sag);
  const int left = 3 * model.node_index(1);  // the left pin's (Rx, Ry)
  EXPECT_NEAR(std::abs(step.reactions[left]), H, 5e-3 * H);
  EXPECT_NEAR(step.reactions[left + 1], q * span / 2.0, 1e-6 * q * span);
  expect_global_equilibrium(model, step);
}

TEST(StraightCable, WhereCutbackRunsOutTheFailureSaysHowToGoOn) {
  // 8e6 N/m: the first iterate from the straight state runs away at any step down to 2⁻¹⁰ of the
  // load; with 14 halvings allowed the cable converges, and carries its weight.
  const double q = 8.0e6;
  tsm::Model model;
  const auto failed = run(straight_cable(q), model);
  ASSERT_EQ(failed.status, tsm::solver::Status::cutback_limit);
  EXPECT_NE(failed.message.find("analysis.max_cutbacks"), std::string::npos) << failed.message;
  json more = straight_cable(q);
  more["analysis"]["max_cutbacks"] = 14;
  const auto r = run(more, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  EXPECT_DOUBLE_EQ(r.steps.back().load_factor, 1.0);
  EXPECT_NEAR(r.steps.back().reactions[3 * model.node_index(1) + 1], q * span / 2.0, 1e-6 * q * span);
  expect_global_equilibrium(model, r.steps.back());
}

}  // namespace
