// Contacts landing together (contact/landing.hpp), end to end: a flexible beam pressed onto a
// stiff one, whose first iterate would carry it metres through the lower beam, lands in each of
// its steps without a cutback and ends where smaller steps end.
#include <gtest/gtest.h>

#include <cmath>

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

/// The continuous press of `length` m under `q` (N/m) in `steps` load steps without a cutback: converged,
/// in equilibrium, and bending the lower beam as its spans bend. Far from the ends the upper
/// beam, 200 × as flexible, lies on the lower one and hands it its whole load: an inner span of a
/// continuous beam under q deflects at its middle by q L⁴ / (384 EI) — with the upper beam's EI
/// alongside and the Timoshenko shear qL²/(8 G A_s), 0.3 % off that; within 1 %.
void expect_press_bends_as_its_spans(int length, double q, int steps) {
  const double L = 10.0, EI = 2e11 * 2e-5;
  const double middle = 10.0 * (length / 20) - 5.0;  // of an inner span near the beam's middle
  json m = continuous_press(length, -q, steps);
  m["analysis"]["cutback"] = false;
  tsm::Model model;
  const RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  const tsm::solver::StepRecord& last = r.steps.back();
  expect_equilibrium(model, last);
  const auto node_at = [&](double x, double y) {
    for (size_t i = 0; i < model.nodes.size(); ++i)
      if ((model.nodes[i].position - Eigen::Vector2d(x, y)).norm() < 1e-9) return static_cast<int>(i);
    ADD_FAILURE() << "no node at " << x << ", " << y;
    return 0;
  };
  const double w = -last.displacements[3 * node_at(middle, 0.0) + 1];
  EXPECT_NEAR(w, q * std::pow(L, 4) / (384.0 * EI), 0.01 * q * std::pow(L, 4) / (384.0 * EI));
  // the supports' rows stay at rest
  EXPECT_NEAR(last.displacements[3 * node_at(middle - 5.0, 0.0) + 1], 0.0, 1e-12);
}

TEST(ContactLanding, ThreeThousandContactNodesLandOnAContinuousBeamInOneStepAndBendItAsItsSpansBend) {
  // The 300-m continuous press (3,001 contact nodes on 9,000 lower elements) in one step to
  // 200 N/m. The landing cuts the first iterates short, and the contacts that start on the way
  // are left as deep as the cut leaves them: along the bent beam's normal their Y (that depth,
  // not the beam's force) turned the normals and Newton's next correction ran the lower beam's
  // roller end metres sideways; the step failed at its fourth iterate with points hopping
  // (cutback to λ = 2·10⁻⁴ and 22 steps where it was allowed). Those iterates push along the
  // chords' normals, and the release look-ahead, once only below 2,000 contacts in touch, frees
  // the lift-off zones at both ends together.
  expect_press_bends_as_its_spans(300, 200.0, 1);
}

TEST(ContactLanding, ThreeThousandContactNodesPressedToTheFullLoadInTenStepsNeedNoCutback) {
  // The same press to 2 kN/m in ten steps (the target's). Far from the solution the points' Y
  // measure how deep the iterates ran them, up to the stiffness cap, and along the bent beam's
  // normal each pushed sideways by Y·w' unseen by the tangent: two steps ran points back and
  // forth over beam nodes and were cut back. Far iterates of many points push along the chords.
  expect_press_bends_as_its_spans(300, 2000.0, 10);
}

TEST(ContactLanding, FiveThousandContactNodesBesideTheLowerBeamsNodesPressedInTenStepsNeedNoCutback) {
  // The 500-m press: its upper nodes pass from 5 mm beside the lower beam's nodes to over them.
  // The landing leaves the points it starts up to two lower elements deep, and the iterate after
  // it pushed them out with Y ~10⁵ times the beam's force: the lower beam moved by millimetres an
  // iterate, points hopped over its nodes, and two attempts of the first step were cut back (12
  // steps). The points landed are put back on the surface (contact::landing_move).
  expect_press_bends_as_its_spans(500, 2000.0, 10);
}

TEST(ContactLanding, AStripOfThreePointsAnElementLetsItsEndsLiftWithoutCutback) {
  // A 6-m strip (130 Timoshenko elements, EI 10⁴, pinned and on a roller 1 cm above the surface)
  // pressed by 3 kN/m onto a 47-element beam (EI 4·10⁶): 2–3 of its points on each lower
  // element. Held down everywhere at first, its ends lift off over a metre or so; the release
  // look-ahead skipped elements with several points, and Newton let go 2–4 points per converged
  // iterate: the first step was cut back 7 times (15 steps, 252 iterations). The forecast takes
  // each element's point stiffness C⁻¹ whole. Far from the ends the strip hands the lower beam
  // its load: the middle deflects 5qL⁴/384EI (both EIs, the strip's lifted ends carrying a part:
  // 0.4 % less), within 1 %.
  const json m = {{"materials", {{"steel", {{"E", 2e11}, {"nu", 0.3}}}}},
                  {"sections", {{"beam", {{"A", 4e-3}, {"I", 2e-5}, {"shear_area", 3.3e-3}}},
                                {"strip", {{"A", 5e-4}, {"I", 5e-8}, {"shear_area", 4e-4}}}}},
                  {"nodes", json::array({{{"id", 1}, {"x", 0.0}, {"y", 0.0}}, {{"id", 2}, {"x", 6.0}, {"y", 0.0}},
                                         {{"id", 3}, {"x", 0.013}, {"y", 0.03}}, {{"id", 4}, {"x", 5.987}, {"y", 0.03}}})},
                  {"members", json::array({{{"from", 1}, {"to", 2}, {"divisions", 47}, {"material", "steel"}, {"section", "beam"}},
                                           {{"from", 3}, {"to", 4}, {"divisions", 130}, {"material", "steel"}, {"section", "strip"},
                                            {"element", "timoshenko"}, {"load", {{"fy", -3000.0}}}}})},
                  {"supports", json::array({{{"node", 1}, {"type", "pinned"}}, {{"node", 2}, {"type", "roller-x"}},
                                            {{"node", 3}, {"type", "pinned"}}, {{"node", 4}, {"type", "roller-x"}}})},
                  {"contacts", json::array({{{"nodes", {{"members", {1}}}}, {"members", {0}}, {"gap", 0.02}}})},
                  {"analysis", {{"control", {{"type", "load"}, {"steps", 4}}}, {"cutback", false}}}};
  tsm::Model model;
  const RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  ASSERT_EQ(r.steps.size(), 4u);
  const tsm::solver::StepRecord& last = r.steps.back();
  expect_equilibrium(model, last);
  int middle = -1, lifted = 0;
  for (size_t i = 0; i < model.nodes.size(); ++i)
    if (model.nodes[i].position.isApprox(Eigen::Vector2d(6.0 * 23.0 / 47.0, 0.0))) middle = static_cast<int>(i);
  ASSERT_GE(middle, 0);
  for (const tsm::solver::ContactPoint& c : last.contacts) lifted += c.element < 0;
  const double EI = 2e11 * (2e-5 + 5e-8), q = 3000.0, L = 6.0, x = 6.0 * 23.0 / 47.0;
  const double w = q * x * (L * L * L - 2.0 * L * x * x + x * x * x) / (24.0 * EI);  // at node 24 (x = 2.94 m)
  EXPECT_NEAR(-last.displacements[3 * middle + 1], w, 0.01 * w);
  EXPECT_GE(lifted, 20);  // both ends off the surface
}

TEST(ContactLanding, AThousandContactNodesTakeTheFullLoadInOneStep) {
  // The 100-m press (1,001 contact nodes on 3,000 lower elements) to 2 kN/m in one step: the
  // issue's "the press in one step". Its far iterates push along the chords (≥ 200 points in
  // touch); along the bent normals the step was cut back five times (6 steps, 98 iterations).
  expect_press_bends_as_its_spans(100, 2000.0, 1);
}

}  // namespace
}  // namespace test_landing_end_to_end

namespace test_landing_sliding_terms {
namespace {

using namespace tsm::test;

TEST(ContactSlidingTerms, AThousandPointsSlidingConvergeQuadraticallyOnceTheirSetHasSettled) {
  // The 100-m press in one step (997 points in touch, most sliding along their elements): near
  // the solution Newton's tangent holds their sliding terms (the node-block LU), so an iterate
  // that neither changes the contacts nor starts from far squares the residual: r' ≤ 100 r², or
  // reaches the tolerance. Left out beyond 32 points (the symmetric part alone, lagged), the
  // tail was linear: 4.4e-5 → 2.3e-7 → 2.6e-9, 1.4e-5 → 2.9e-8, 3.1e-5 → 4.7e-7.
  json m = continuous_press(100, -2000.0, 1);
  m["analysis"]["cutback"] = false;
  tsm::Model model;
  const tsm::solver::RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  const std::vector<double>& residual = r.steps.back().residual_norms;
  const double tolerance = model.analysis.tolerance;
  int pairs = 0;
  for (size_t k = 1; k + 1 < residual.size(); ++k) {
    if (residual[k] >= 1e-4 || residual[k + 1] >= residual[k]) continue;  // far, or the contacts changed
    ++pairs;
    EXPECT_TRUE(residual[k + 1] <= 100.0 * residual[k] * residual[k] || residual[k + 1] <= tolerance)
        << "iterate " << k << ": " << residual[k] << " → " << residual[k + 1];
  }
  EXPECT_GE(pairs, 2);
}

}  // namespace
}  // namespace test_landing_sliding_terms
