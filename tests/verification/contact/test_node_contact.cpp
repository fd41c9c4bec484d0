// A push on a beam node (a vertex: the contact on both elements meeting there) end to end: the
// linear force and symmetry, a far stiffer member under it, short elements, and the vertex
// opening as a whole when the beam returns.
#include <gtest/gtest.h>

#include <string>

#include "support/contact_models.hpp"

namespace {

using namespace tsm::test;
using tsm::solver::RunResult;
using tsm::solver::StepRecord;

// ---- A point resting on a beam node: both elements hold it (contact/vertex.hpp) ----

/// A pinned–pinned beam (10 m, steel) of `divisions` elements and a rigid pusher node 100 above
/// mid-span at height y0, moved down by `push` (its x held).
json simply_supported_push(int divisions, const char* element, double y0, double push, int steps) {
  BeamSpec b{.L = 10.0, .E = 2.0e11, .G = 7.7e10, .A = 4.0e-3, .I = 2.0e-5, .shear_area = 2.0e-3,
             .divisions = divisions, .element = element};
  json m = pusher_model(b, 5.0, y0, 0.0, push, steps);
  m["supports"] = json::array({{{"node", 1}, {"type", "pinned"}}, {{"node", 2}, {"type", "pinned"}},
                               {{"node", 100}, {"fix", json::array({"ux", "rz"})}}});
  return m;
}

class ContactOnANode : public ::testing::TestWithParam<const char*> {};

TEST_P(ContactOnANode, ASymmetricPushOnABeamNodeRestsOnBothElementsWithTheLinearForce) {
  // A push exactly on the mid-span node of 20 elements: on either element alone the force,
  // normal to its chord, pushes the point over the node onto the other (the chords meet at an
  // angle), so it rests on the node with both elements in contact (a vertex). Before the vertex
  // the run failed with "contact points keep hopping" at a push of 1 mm. A beam node under a
  // point load is exact for both element kinds, so the linear formula
  // P = δ / (L³/48EI + L/(4 G A_s)) (no shear term for Euler–Bernoulli) holds to the
  // membrane effect of a 1 mm push, ~1e-5 here.
  const bool timoshenko = std::string(GetParam()) == "timoshenko";
  const double delta = 1e-3, L = 10.0, EI = 2.0e11 * 2.0e-5, GAs = 7.7e10 * 2.0e-3;
  const double P = delta / (L * L * L / (48.0 * EI) + (timoshenko ? L / (4.0 * GAs) : 0.0));
  for (int steps : {1, 4}) {
    tsm::Model model;
    const RunResult r = run(simply_supported_push(20, GetParam(), 0.0, -delta, steps), model);
    ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
    const StepRecord& last = r.steps.back();
    const tsm::solver::ContactPoint& c = contact_of(last);
    const int middle = beam_node_at(model, 5.0);
    ASSERT_GE(c.element, 0);
    ASSERT_GE(c.partner, 0) << "a contact on one element only";
    EXPECT_EQ(model.elements[c.element].end, middle);  // reported on the element ending at the node …
    EXPECT_EQ(c.alpha, 1.0);                           // … at its end
    EXPECT_EQ(model.elements[c.partner].start, middle);
    EXPECT_NEAR(c.force, P, 1e-4 * P);
    const int pusher = model.node_index(100);
    EXPECT_NEAR(last.reactions[3 * pusher + 1], -P, 1e-4 * P);
    EXPECT_NEAR(last.reactions[3 * pusher], 0.0, 1e-9 * P);  // symmetric: no sideways push
    EXPECT_NEAR(node_displacement(model, last, model.nodes[middle].id)[1], -delta, 1e-9 * delta);
    expect_equilibrium(model, last);
  }
}

TEST_P(ContactOnANode, ALargePushOnABeamNodeStaysSymmetric) {
  // The same push to 1 m (the beam stretched, the chords at the node 4° apart): the vertex holds
  // to the end, the answer mirror-symmetric, and near that of 21 elements, whose mid-span is
  // mid-element (no vertex): the meshes differ, so only to their discretisation error.
  tsm::Model model, odd_model;
  const RunResult r = run(simply_supported_push(20, GetParam(), 0.001, -1.0, 20), model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  const RunResult odd = run(simply_supported_push(21, GetParam(), 0.001, -1.0, 20), odd_model);
  ASSERT_EQ(odd.status, tsm::solver::Status::converged) << odd.message;
  const StepRecord& last = r.steps.back();
  const int left = model.node_index(1), right = model.node_index(2), pusher = model.node_index(100);
  const double force = contact_of(last).force;
  ASSERT_GE(contact_of(last).partner, 0);
  EXPECT_NEAR(last.reactions[3 * left + 1], last.reactions[3 * right + 1], 1e-9 * force);
  EXPECT_NEAR(last.reactions[3 * left], -last.reactions[3 * right], 1e-9 * force);
  EXPECT_NEAR(last.reactions[3 * pusher], 0.0, 1e-9 * force);
  EXPECT_NEAR(force, contact_of(odd.steps.back()).force, 0.015 * force);
  for (const StepRecord& s : r.steps) expect_equilibrium(model, s);
}

INSTANTIATE_TEST_SUITE_P(Kinds, ContactOnANode, ::testing::Values("euler-bernoulli", "timoshenko"));

TEST(ContactOnANode, AContactOnAFarStifferMemberIsCappedOrNamedAsTooStiffToResolve) {
  // A post (A 1e-3, 0.5 m, clamped at its top) whose foot rests at the gap on the middle node of
  // a slab clamped at both ends (2 m, 20 elements, I = 1 m⁴: 10⁷ × the post's), 10 kN on the
  // foot. At a beam node the contact's compliance is the floor the contact's `edge` sets, on the
  // slab's EI: 1/c ≈ 6e20, so rounding of the coordinates alone leaves ~10⁴ N in its force —
  // unresolvable. The contact's stiffness cap (max_stiffness_ratio, 10⁴ × the post's element's
  // EA/l by default) keeps it resolvable: the contact carries what the two springs in series
  // give, the slab's 192EI/L³ against the post's EA/L, to the cap's own compliance (1/(2e13), 2e-5
  // of the post's). Uncapped, the run said only that the loads were too small (found squeezing
  // a ring between stiff plates); it now names the contact, its stiffness and the edge; with
  // edge 0.1 the floor is 10⁶ × softer and it converges.
  json m = {{"materials", {{"steel", {{"E", 2e11}, {"nu", 0.3}}}}},
            {"sections", {{"post", {{"A", 1e-3}, {"I", 1e-7}}}, {"slab", {{"A", 0.1}, {"I", 1.0}}}}},
            {"nodes", json::array({{{"id", 1}, {"x", 0.0}, {"y", 0.0}}, {{"id", 2}, {"x", 2.0}, {"y", 0.0}},
                                   {{"id", 3}, {"x", 1.0}, {"y", 0.51}}, {{"id", 4}, {"x", 1.0}, {"y", 0.01}}})},
            {"members", json::array({{{"from", 1}, {"to", 2}, {"divisions", 20}, {"material", "steel"}, {"section", "slab"}},
                                     {{"from", 3}, {"to", 4}, {"divisions", 5}, {"material", "steel"}, {"section", "post"}}})},
            {"supports", json::array({{{"node", 1}, {"type", "fixed"}}, {{"node", 2}, {"type", "fixed"}},
                                      {{"node", 3}, {"type", "fixed"}}})},
            {"loads", json::array({{{"node", 4}, {"fy", -1e4}}})},
            {"contacts", json::array({{{"node", 4}, {"members", {0}}, {"gap", 0.01}}})},
            {"analysis", {{"control", {{"type", "load"}, {"steps", 1}}}}}};
  tsm::Model model;
  const double k_slab = 192.0 * 2e11 * 1.0 / 8.0, k_post = 2e11 * 1e-3 / 0.5, P = 1e4;
  const RunResult capped = run(m, model);
  ASSERT_EQ(capped.status, tsm::solver::Status::converged) << capped.message;
  EXPECT_NEAR(contact_of(capped.steps.back()).force, P * k_slab / (k_slab + k_post), 1e-4 * P);
  m["contacts"][0]["max_stiffness_ratio"] = 1e12;
  const RunResult stiff = run(m, model);
  ASSERT_NE(stiff.status, tsm::solver::Status::converged);
  EXPECT_NE(stiff.message.find("most of that rounding is in the force of the contact at node 4"), std::string::npos)
      << stiff.message;
  EXPECT_NE(stiff.message.find("the point is at a beam node, where the contact's \"edge\" sets that compliance"),
            std::string::npos)
      << stiff.message;
  m["contacts"][0]["edge"] = 0.1;
  const RunResult softened = run(m, model);
  ASSERT_EQ(softened.status, tsm::solver::Status::converged) << softened.message;
  EXPECT_NEAR(contact_of(softened.steps.back()).force, P * k_slab / (k_slab + k_post), 1e-4 * P);
  // A ratio of 10¹¹ caps it at 1/c = 2e20, below the edge's 6e20 but still beyond what rounding
  // resolves (10¹⁰ converges): the message names the cap.
  m["contacts"][0].erase("edge");
  m["contacts"][0]["max_stiffness_ratio"] = 1e11;
  const RunResult at_cap = run(m, model);
  ASSERT_NE(at_cap.status, tsm::solver::Status::converged);
  EXPECT_NE(at_cap.message.find("(1/c = 2e+20; a member far stiffer than what presses on it makes it so): that is the "
                                "contact's cap, \"max_stiffness_ratio\" times the stiffest element holding its node"),
            std::string::npos)
      << at_cap.message;
}

TEST(ContactOnANode, AStiffContactAtANodeOfShortElementsIsNotAcceptedUnconverged) {
  // examples/contact-push.json's cantilever with 10,000 elements (0.9 mm): the pusher starts on
  // a beam node, pushed 5 mm in one step. Held at that node by both elements, the contact is so
  // stiff (compliance ~1e-23 m/N) that Newton's corrections fell to rounding level with the
  // residual still at 0.5 of the load, and the step ended "on round-off" with 2.6× the force.
  // Round-off now needs a relative residual below 1e-3: the step is cut back and converges to
  // the linear answer P = δ / (a³/3EI + a/GA_s) (the membrane effect of 5 mm: ~1e-5).
  BeamSpec b{.L = 9.0, .E = 2.05e11, .G = 7.9e10, .A = 1e-2, .I = 1e-4, .shear_area = 8.3e-3, .divisions = 10000,
             .element = "timoshenko"};
  tsm::Model model;
  const RunResult r = run(pusher_model(b, 4.05, 0.0, 0.0, 0.005, 1), model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  for (const StepRecord& s : r.steps) EXPECT_LT(s.residual_norms.back(), 1e-3) << "step " << s.step << " (" << criterion_name(s.criterion) << ")";
  const double a = 4.05, P = 0.005 / (a * a * a / (3.0 * 2.05e11 * 1e-4) + a / (7.9e10 * 8.3e-3));
  EXPECT_NEAR(contact_of(r.steps.back()).force, P, 1e-4 * P);
}

TEST_P(ContactOnANode, ThePushedBeamReturnsAndTheVertexOpensAsAWhole) {
  // Pushed down 0.5 m onto the node and back up (λ: 0 → 1 → 0): the beam is elastic, so on the
  // way back each λ gives the way down's force; the vertex holds until the pusher is back above
  // the straight beam, where both its elements would pull and it opens as a whole.
  tsm::Model model;
  json m = simply_supported_push(20, GetParam(), 0.001, -0.5, 10);
  m["analysis"]["control"]["path"] = {1.0, 0.0};
  const RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  ASSERT_EQ(r.steps.size(), 20u);
  for (int k = 0; k < 9; ++k) {  // step k+1 down and step 19−k up are at the same λ
    const StepRecord &down = r.steps[k], &up = r.steps[18 - k];
    ASSERT_NEAR(down.load_factor, up.load_factor, 1e-12);
    if (down.load_factor * 0.5 <= 0.001) continue;  // not touching yet
    ASSERT_GE(contact_of(down).partner, 0) << "step " << down.step;
    ASSERT_GE(contact_of(up).partner, 0) << "step " << up.step;
    EXPECT_NEAR(contact_of(up).force, contact_of(down).force, 1e-6 * contact_of(down).force) << "step " << up.step;
  }
  const StepRecord& last = r.steps.back();
  EXPECT_LT(contact_of(last).element, 0);
  EXPECT_LT(last.displacements.cwiseAbs().maxCoeff(), 1e-9);
}

}  // namespace
