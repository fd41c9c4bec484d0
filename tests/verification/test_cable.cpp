// A cable modelled straight: 40 elements of steel wire (A = 1 cm², I next to nothing) pinned at
// both ends 20 m apart, its weight q as a member load, in one load step. The straight start has
// only EI against the load, so Newton's first iterate overshoots by about qL⁴/EI; the cable
// still converges — at its weight against the parabola, at a million times its weight against
// the elastic catenary — and where cutback runs out the failure says how to go on.
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

double lowest_point(const tsm::Model& model, const tsm::solver::StepRecord& step) {
  double lowest = 0.0;
  for (int k = 0; k < model.node_count(); ++k) lowest = std::min(lowest, step.displacements[3 * k + 1]);
  return -lowest;
}

/// The left pin carries the horizontal pull H and half the weight q·span; the whole is in equilibrium.
void expect_pins_hold(const tsm::Model& model, const tsm::solver::StepRecord& step, double H, double H_tolerance, double q) {
  const int left = 3 * model.node_index(1);  // the left pin's (Rx, Ry)
  EXPECT_NEAR(std::abs(step.reactions[left]), H, H_tolerance * H);
  EXPECT_NEAR(step.reactions[left + 1], q * span / 2.0, 1e-6 * q * span);
  expect_global_equilibrium(model, step);
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
  EXPECT_NEAR(lowest_point(model, step), sag, 5e-3 * sag);
  expect_pins_hold(model, step, H, 5e-3, q);
}

/// Irvine's elastic catenary (Cable Structures, 1981): a Hookean cable of unstretched length
/// L0 between level supports `span` apart under w per unstretched length. Its tension T stretches
/// it by T/EA — the elements' law N = EA (l − l0)/l0 — so a fine mesh approaches it at any
/// strain. H from span = H L0/EA + (2H/w) asinh(w L0 / 2H), by bisection.
struct Catenary {
  double H = 0.0, sag = 0.0;
  double tension(double s, double w, double L0) const { return std::hypot(H, w * (L0 / 2.0 - s)); }  ///< at s from an end
};

Catenary elastic_catenary(double w, double L0, double span_, double ea) {
  const double V = w * L0 / 2.0;
  auto span_of = [&](double H) { return H * L0 / ea + 2.0 * H / w * std::asinh(V / H); };
  double low = 1e-12 * V, high = 1e12 * V;  // span_of increases with H
  for (int k = 0; k < 200; ++k) {
    const double mid = std::sqrt(low * high);
    (span_of(mid) > span_ ? high : low) = mid;
  }
  const double H = low;
  return {H, w * L0 * L0 / (8.0 * ea) + H / w * (std::sqrt(1.0 + (V / H) * (V / H)) - 1.0)};
}

TEST(StraightCable, AMillionTimesItsWeightStretchesItAsTheElasticCatenaryInOneStep) {
  // 8e6 N/m stretches the wire by ~400 %: far past a small-strain law, but it is the model's
  // law, and the elastic catenary follows the same one. The first iterate from the straight
  // state overshoots by ~qL⁴/EI (~8e10 m) and comes back; 40 chords carrying nodal loads sit
  // within ~2e-4 of the continuous cable (measured 2.4e-4 for the sag, 2e-5 for H).
  const double q = 8.0e6;
  tsm::Model model;
  const auto r = run(straight_cable(q), model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  ASSERT_EQ(r.steps.size(), 1u);
  const Catenary exact = elastic_catenary(q, span, span, EA);
  const auto& step = r.steps.back();
  EXPECT_NEAR(lowest_point(model, step), exact.sag, 1e-3 * exact.sag);
  expect_pins_hold(model, step, exact.H, 1e-3, q);
  // The largest strain is in an end element (half an element from the pin), and said in a note.
  const double end_strain = exact.tension(span / 80.0, q, span) / EA;
  EXPECT_NEAR(step.axial_strain, end_strain, 1e-3 * end_strain);
  ASSERT_EQ(r.notes.size(), 1u);
  // The note's strain is the step's, in per cent (to the six digits it is written with).
  const std::string said = "the largest axial strain N/EA is ";
  const size_t at = r.notes[0].find(said);
  ASSERT_NE(at, std::string::npos) << r.notes[0];
  const double percent = std::stod(r.notes[0].substr(at + said.size()));
  EXPECT_NEAR(percent, 100.0 * step.axial_strain, 1e-5 * 100.0 * step.axial_strain) << r.notes[0];
  EXPECT_NEAR(percent, 100.0 * end_strain, 1e-3 * 100.0 * end_strain) << r.notes[0];
  EXPECT_NE(r.notes[0].find("tension"), std::string::npos) << r.notes[0];
}

TEST(StraightCable, AtItsWeightNoStrainNote) {
  tsm::Model model;
  const auto r = run(straight_cable(8.0), model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  EXPECT_LT(r.steps.back().axial_strain, 2e-4);  // H/EA ≈ 1.4e-4
  EXPECT_GT(r.steps.back().axial_strain, 1e-4);
  EXPECT_TRUE(r.notes.empty());
}

TEST(StraightCable, WhereCutbackRunsOutTheFailureSaysHowToGoOn) {
  // I = 1e-16 m⁴, ten thousand times less than the wire above: from the straight state the
  // first iterate's stretch blows the unbalanced force up at any step down to 2⁻³⁰ of its
  // weight. With 45 halvings allowed the cable converges (the steps grow again once it sags),
  // and hangs as the catenary.
  const double q = 8.0;
  json thin = straight_cable(q);
  thin["sections"]["wire"]["I"] = 1e-16;
  tsm::Model model;
  const auto failed = run(thin, model);
  ASSERT_EQ(failed.status, tsm::solver::Status::cutback_limit);
  EXPECT_NE(failed.message.find("analysis.max_cutbacks"), std::string::npos) << failed.message;
  // … and why: the cable bends next to nothing against its stretching (EI/(EA l²) = 4e-12 here).
  EXPECT_NE(failed.message.find("elements bend next to nothing against their stretching (EI/(EA l²) down to"),
            std::string::npos)
      << failed.message;
  EXPECT_NE(failed.message.find("such a cable has no stiffness across it until it sags"), std::string::npos) << failed.message;
  thin["analysis"]["max_cutbacks"] = 45;
  const auto r = run(thin, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  EXPECT_DOUBLE_EQ(r.steps.back().load_factor, 1.0);
  const Catenary exact = elastic_catenary(q, span, span, EA);
  EXPECT_NEAR(lowest_point(model, r.steps.back()), exact.sag, 1e-3 * exact.sag);
  expect_global_equilibrium(model, r.steps.back(), 1e-8);  // its last step ended at 7e-9, within the run's tolerance
}

}  // namespace
