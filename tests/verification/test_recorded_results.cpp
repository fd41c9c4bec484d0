// What a run keeps: whatever the output selection, the newest converged step carries its whole
// state (displacements, element forces, reactions), the same as a run that keeps every step —
// also when the run stops at a failed step. (Under output "last" the element forces of the
// steps dropped again are never computed: the recorder adds them to the newest step at the end.)
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "support/models.hpp"

namespace test_recorded_results {
namespace {

using namespace tsm::test;
using tsm::solver::RunResult;
using tsm::solver::StepRecord;

RunResult run(json m, const char* output, tsm::Model& model) {
  m["analysis"]["output"] = output;
  model = tsm::io::read_model(m);
  return tsm::solver::run_analysis(model);
}

const StepRecord& newest_converged(const RunResult& r) {
  for (auto s = r.steps.rbegin(); s != r.steps.rend(); ++s)
    if (s->converged) return *s;
  throw std::runtime_error("no converged step");
}

void expect_same_state(const StepRecord& a, const StepRecord& b) {
  ASSERT_TRUE(a.has_state && b.has_state);
  EXPECT_EQ(a.step, b.step);
  EXPECT_TRUE((a.displacements.array() == b.displacements.array()).all());
  ASSERT_EQ(a.element_forces.size(), b.element_forces.size());
  EXPECT_TRUE((a.element_forces.array() == b.element_forces.array()).all());
  EXPECT_TRUE((a.reactions.array() == b.reactions.array()).all());
}

TEST(RecordedResults, TheLastStepKeepsItsElementForcesUnderOutputLast) {
  // A cantilever rolled to a quarter circle by a tip moment M: every element carries M and no
  // axial force (equilibrium of the part beyond it), exactly.
  const double EI = 2.0, L = 3.0, M = 0.25 * 2.0 * std::numbers::pi * EI / L;
  json m = beam_model({.L = L, .E = 1.0, .G = 0.5, .A = 1e4, .I = EI, .shear_area = 1e3, .divisions = 20});
  m["supports"] = json::array({{{"node", 1}, {"type", "fixed"}}});
  m["loads"] = json::array({{{"node", 2}, {"mz", M}}});
  m["analysis"]["control"] = {{"type", "load"}, {"steps", 4}};
  tsm::Model model;
  const RunResult all = run(m, "all", model), last = run(m, "last", model);
  ASSERT_EQ(all.status, tsm::solver::Status::converged) << all.message;
  ASSERT_EQ(last.status, tsm::solver::Status::converged) << last.message;
  for (size_t k = 0; k + 1 < last.steps.size(); ++k) EXPECT_FALSE(last.steps[k].has_state) << k;
  expect_same_state(all.steps.back(), last.steps.back());
  const Eigen::VectorXd& forces = last.steps.back().element_forces;
  ASSERT_EQ(forces.size(), 3 * 20);
  for (int e = 0; e < 20; ++e) {
    EXPECT_NEAR(forces[3 * e], 0.0, 1e-8 * M / L) << "N of element " << e;
    EXPECT_NEAR(std::abs(forces[3 * e + 1]), M, 1e-9 * M) << "M_i of element " << e;
    EXPECT_NEAR(std::abs(forces[3 * e + 2]), M, 1e-9 * M) << "M_j of element " << e;
  }
}

TEST(RecordedResults, AFailedRunKeepsTheNewestConvergedStepWhole) {
  // The quarter-circle cantilever on a load path: two small steps to 1 % of the moment, then
  // two steps of many turns each, which 6 iterations cannot reach (no cutback): the run stops
  // at step 3 and keeps step 2.
  const double EI = 2.0, L = 3.0, M = 0.25 * 2.0 * std::numbers::pi * EI / L;
  json m = beam_model({.L = L, .E = 1.0, .G = 0.5, .A = 1e4, .I = EI, .shear_area = 1e3, .divisions = 20});
  m["supports"] = json::array({{{"node", 1}, {"type", "fixed"}}});
  m["loads"] = json::array({{{"node", 2}, {"mz", M}}});
  m["analysis"]["control"] = {{"type", "load"}, {"steps", 2}, {"path", {0.01, 8.0}}};
  m["analysis"]["cutback"] = false;
  m["analysis"]["max_iterations"] = 6;
  tsm::Model model;
  const RunResult all = run(m, "all", model), last = run(m, "last", model);
  ASSERT_NE(last.status, tsm::solver::Status::converged);
  ASSERT_FALSE(last.steps.back().converged);
  const StepRecord& kept = newest_converged(last);
  EXPECT_EQ(kept.step, 2);
  expect_same_state(newest_converged(all), kept);
  for (int e = 0; e < 20; ++e) EXPECT_NEAR(std::abs(kept.element_forces[3 * e + 1]), 0.01 * M, 1e-9 * M) << e;
}

TEST(RecordedResults, HowContactsMovedPerIterateGoesToTheObserverAndIsNotKept) {
  // Contact points per iterate (what --log-iterations prints) for every contact at every iterate
  // of every step: the observer sees them, the records the run returns do not keep them (they
  // grew with contacts × iterations × steps: 213 MB of a run of 5,001 contacts).
  tsm::Model model = tsm::io::read_model(pressed_beams(-2000.0, 4, 60, 20));
  size_t observed = 0;
  const RunResult r = tsm::solver::run_analysis(model, [&](const StepRecord& step) {
    if (step.contact_iterates.size() == static_cast<size_t>(step.iterations) + 1 &&
        step.contact_iterates.front().size() == model.contacts.size())
      ++observed;
  });
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  EXPECT_EQ(observed, r.steps.size());
  for (const StepRecord& step : r.steps) EXPECT_TRUE(step.contact_iterates.empty()) << "step " << step.step;
}

TEST(RecordedResults, AnAttemptCutBackIsShownToTheObserverWithWhyAndIsNotKept) {
  // The pressed beams under their whole load in one step: attempts fail and are cut back before
  // the steps converge. Each goes to the observer — not converged, marked cut back, why in its
  // message, its load factor the attempt's start — and none is kept: as many as the kept steps'
  // cutbacks.
  tsm::Model model = tsm::io::read_model(pressed_beams(-2000.0, 1));
  std::vector<StepRecord> attempts;
  std::vector<double> converged_at{0.0};
  const RunResult r = tsm::solver::run_analysis(model, [&](const StepRecord& step) {
    if (step.cut_back) {
      attempts.push_back(step);
      EXPECT_EQ(step.load_factor, converged_at.back());
    } else if (step.converged) {
      converged_at.push_back(step.load_factor);
    }
  });
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  int cutbacks = 0;
  for (const StepRecord& step : r.steps) {
    cutbacks += step.cutbacks;
    EXPECT_FALSE(step.cut_back) << "step " << step.step;
  }
  EXPECT_GT(cutbacks, 0);
  EXPECT_EQ(attempts.size(), static_cast<size_t>(cutbacks));
  for (const StepRecord& a : attempts) {
    EXPECT_FALSE(a.converged);
    EXPECT_FALSE(a.message.empty());
    EXPECT_GT(a.iterations, 0);
  }
}

}  // namespace

}  // namespace test_recorded_results
