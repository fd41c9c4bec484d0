// Release end to end: a pusher pulled back lets go at zero force and the beam returns straight.
#include <gtest/gtest.h>

#include <string>

#include "support/contact_models.hpp"

namespace {

using namespace tsm::test;
using tsm::solver::RunResult;
using tsm::solver::StepRecord;

TEST(ContactRelease, PullingBackReleasesAtZeroForceAndTheBeamReturnsStraight) {
  // Pusher 0.0123 below the beam, pushed 0.05 up and back down (λ: 0 → 1 → 0).
  BeamSpec b;
  b.divisions = 20;
  b.A = 1e6;
  tsm::Model model;
  json m = pusher_model(b, 0.6, -0.0123, 0.0, 0.05, 20);
  m["analysis"]["control"]["path"] = {1.0, 0.0};
  const RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  ASSERT_EQ(r.steps.size(), 40u);
  const double flexibility = 0.6 * 0.6 * 0.6 / 3.0;  // EI = 1
  int active_steps = 0;
  for (const StepRecord& s : r.steps) {
    const double lift = 0.05 * s.load_factor - 0.0123;  // pusher above the straight beam
    const tsm::solver::ContactPoint& c = contact_of(s);
    if (lift < 0.0) {
      EXPECT_LT(c.element, 0) << "step " << s.step << ": in contact while below the beam";
      EXPECT_LT(s.displacements.cwiseAbs().maxCoeff(), 1e-12 + 0.06) << "step " << s.step;
      // only the pusher moves; the beam is straight
      for (int k = 0; k < model.node_count(); ++k)
        if (model.nodes[k].id != 100) EXPECT_LT(s.displacements.segment<3>(3 * k).norm(), 1e-12) << "node " << model.nodes[k].id;
    } else {
      ++active_steps;
      ASSERT_GE(c.element, 0) << "step " << s.step;
      // Small lifts: the force follows the linear law down to zero (within geometric effects).
      if (lift < 0.005) EXPECT_NEAR(c.force, lift / flexibility, 2e-3 * lift / flexibility) << "step " << s.step;
    }
  }
  EXPECT_EQ(active_steps, 2 * 16 - 1);  // λ = 0.25 … 1 on the way up and back down
  // Out of contact the beam carries nothing: those steps' relative residuals are rounding noise
  // (up to ~1), and the run says so once, rather than leave them to look like failures.
  int quiet = 0;
  for (const StepRecord& s : r.steps) quiet += s.criterion == tsm::solver::Criterion::nothing_carried ? 1 : 0;
  EXPECT_GT(quiet, 0);
  ASSERT_FALSE(r.notes.empty());
  EXPECT_NE(r.notes.front().find("the structure carried next to nothing"), std::string::npos) << r.notes.front();
  EXPECT_NE(r.notes.front().find(std::to_string(quiet) + " steps from"), std::string::npos) << r.notes.front();
}

}  // namespace
