// The contact set (contact/contact_set.cpp) driven by hand, not by a run: a vertex's sides letting
// go at a converged iterate, contact only where the node's own path crossed an element, and
// after a release by a pull, through the beam (or a ring) only where the node is.
#include <gtest/gtest.h>

#include <numbers>
#include <vector>

#include <Eigen/Core>

#include "support/contact_models.hpp"
#include "tsmframe/assembly/dof_map.hpp"
#include "tsmframe/assembly/global_system.hpp"
#include "tsmframe/contact/contact_set.hpp"

namespace {

using namespace tsm::test;

// ---- A vertex: two contact elements at one node ----

TEST(ContactVertex, ASidePullingAtAConvergedIterateLetsGoAndBothPullingRelease) {
  VertexSetUp v = vertex_set_up("timoshenko");
  tsm::contact::ContactSet tracker(v.model);
  tsm::assembly::DofMap dofs(v.model);
  tsm::assembly::GlobalSystem system(v.model, dofs);
  std::vector<double> rotations(v.model.elements.size(), 0.0);
  tsm::assembly::Evaluation e;
  system.evaluate(v.D, rotations, false, e);
  const tsm::contact::StepStart unloaded = tsm::contact::unloaded_start(v.model);  // the references' state
  // Compression is −side·Y: with side −1 a positive Y presses, a negative one pulls.
  using E = tsm::contact::ContactEvaluation;
  {
    auto states = v.states;  // both press: nothing changes, even at a converged iterate
    const auto normal = [&](int element) {
      const tsm::Element& f = v.model.elements[element];
      const Eigen::Vector2d a = v.model.nodes[f.start].position + v.D.segment<2>(3 * f.start);
      const Eigen::Vector2d b = v.model.nodes[f.end].position + v.D.segment<2>(3 * f.end);
      const Eigen::Vector2d t = (b - a).normalized();
      return Eigen::Vector2d(-t.y(), t.x());
    };
    // Each element's push on the node (its nodal force there: here along its chord's normal).
    const E first{0, false, 1.0, 5.0, 1.0, 5.0 * normal(v.ending)}, second{0, true, 0.0, 3.0, 1.0, 3.0 * normal(v.starting)};
    EXPECT_FALSE(tracker.update(v.D, e.chord_rotations, {first, second}, states, true, unloaded).any());
    ASSERT_TRUE(states[0].vertex);
    EXPECT_EQ(states[0].vertex->element, v.starting);
    // Reported: the compression of the resultant of the pushes, 5 n_ending + 3 n_starting.
    const double resultant = (5.0 * normal(v.ending) + 3.0 * normal(v.starting)).norm();
    EXPECT_LT(resultant, 7.999);  // the chords meet at an angle (0.1 rad here)
    EXPECT_NEAR(states[0].force, resultant, 1e-12 * resultant);
    EXPECT_EQ(states[0].alpha, 1.0);  // on the element ending at the node, at its end
  }
  {
    auto states = v.states;  // one pulls, but the iterate has not converged: held
    EXPECT_FALSE(tracker.update(v.D, e.chord_rotations, {E{0, false, 1.0, 5.0}, E{0, true, 0.0, -3.0}}, states, false, unloaded).any());
    ASSERT_TRUE(states[0].vertex);
    EXPECT_EQ(states[0].vertex->element, v.starting);
  }
  {
    auto states = v.states;  // the starting element pulls: the ending one carries on alone, held at the node
    const auto changes = tracker.update(v.D, e.chord_rotations, {E{0, false, 1.0, 5.0}, E{0, true, 0.0, -3.0}}, states, true, unloaded);
    EXPECT_EQ(changes.released, 1);
    EXPECT_TRUE(states[0].active);
    EXPECT_EQ(states[0].element, v.ending);
    EXPECT_FALSE(states[0].vertex);
    EXPECT_EQ(states[0].step.held_node, v.node);
  }
  {
    auto states = v.states;  // the ending element pulls: the starting one carries on
    tracker.update(v.D, e.chord_rotations, {E{0, false, 1.0, -5.0}, E{0, true, 0.0, 3.0}}, states, true, unloaded);
    EXPECT_EQ(states[0].element, v.starting);
    EXPECT_EQ(states[0].side, -1);
    EXPECT_FALSE(states[0].vertex);
  }
  {
    auto states = v.states;  // both pull: released
    tracker.update(v.D, e.chord_rotations, {E{0, false, 1.0, -5.0}, E{0, true, 0.0, -3.0}}, states, true, unloaded);
    EXPECT_FALSE(states[0].active);
    EXPECT_FALSE(states[0].vertex);
  }
}

// ---- Released by a pull: the side it let go on holds for the whole beam ----

TEST(ContactDetection, AlongTheNodesPathOnlyWhereTheNodeItselfCrossedTheElement) {
  // The tracker alone, on a 4-element cantilever (0 … 1 along x) and a contact node that starts
  // 0.02 above it at x = 0.125. (a) An iterate throws the node to (1.5, −0.02), past the free end:
  // it ends within no element's span, but its path crossed element 2's chord from above — contact
  // starts there and is carried along the beam to its free end (held there until a converged
  // iterate lets it go). (b) The node stays put outside the beam (x = −0.25) while the beam turns
  // half a turn about its middle: in element 1's own frame the node passed from one side to the
  // other within its span, but the node never met it — no contact.
  BeamSpec b;
  b.divisions = 4;
  const tsm::Model model = tsm::io::read_model(pusher_model(b, 0.125, 0.02, 0.0, -0.02, 1));
  tsm::contact::ContactSet tracker(model);
  const std::vector<double> straight(model.elements.size(), 0.0);
  const int pusher = model.node_index(100);
  {
    std::vector<tsm::contact::ContactState> states = tracker.initial_states();
    Eigen::VectorXd D = Eigen::VectorXd::Zero(model.dof_count());
    const tsm::contact::StepStart start = tsm::contact::unloaded_start(model);  // where initial_states took the references
    D.segment<2>(3 * pusher) = Eigen::Vector2d(1.5 - 0.125, -0.04);
    const tsm::contact::ContactChanges changes = tracker.update(D, straight, {}, states, false, start);
    EXPECT_EQ(changes.activated, 1);
    ASSERT_TRUE(states[0].active) << "the node's path crossed the beam";
    EXPECT_EQ(states[0].side, 1);  // from above
    EXPECT_EQ(states[0].element, 3) << "carried on to the free end";
  }
  {
    json m = pusher_model(b, -0.25, 0.02, 0.0, -0.02, 1);
    const tsm::Model outside = tsm::io::read_model(m);
    tsm::contact::ContactSet outside_tracker(outside);
    std::vector<tsm::contact::ContactState> states = outside_tracker.initial_states();
    Eigen::VectorXd D = Eigen::VectorXd::Zero(outside.dof_count());
    const tsm::contact::StepStart start = tsm::contact::unloaded_start(outside);
    for (int k = 0; k < outside.node_count(); ++k) {
      if (k == outside.node_index(100)) continue;
      const Eigen::Vector2d x = outside.nodes[k].position, turned = Eigen::Vector2d(1.0 - x.x(), -x.y());
      D.segment<3>(3 * k) << turned - x, std::numbers::pi;
    }
    const std::vector<double> half_turn(outside.elements.size(), std::numbers::pi);
    EXPECT_FALSE(outside_tracker.update(D, half_turn, {}, states, false, start).any());
    EXPECT_FALSE(states[0].active);
  }
}

TEST(ContactReferences, ARunsOrAStagesStartTakesEveryReferenceAgainWithTheCandidatesItHasNow) {
  // A stage that turns a contact off leaves it a reference taken with no candidates, at the very
  // displacements the next stage starts from; turned on again, its reference is taken anew
  // (its near list feeds the broad phase and the landing), not kept for its stamp.
  BeamSpec b;
  b.divisions = 4;
  const tsm::Model model = tsm::io::read_model(pusher_model(b, 0.125, 0.02, 0.0, -0.02, 1));
  tsm::contact::ContactSet tracker(model);
  std::vector<tsm::contact::ContactState> states = tracker.initial_states();
  const std::vector<int> near = states[0].reference.near;
  ASSERT_FALSE(near.empty());
  states[0].reference.near.clear();  // as taken while the stage had turned it off
  states[0].reference.side.set({});
  tracker.restore(tsm::contact::unloaded_start(model), states);
  EXPECT_EQ(states[0].reference.near, near);
  EXPECT_EQ(states[0].reference.side.size(), near.size());
}

TEST(ContactRelease, ANodeThatLetGoByPullingMayNotBeThroughTheBeamAnywhere) {
  // A contact on element 3 of a 10-element cantilever, from above, lets go by pulling at an
  // iterate that has thrown the node far beyond the beam (a diverging Newton iterate): no
  // element's span held it then. If a later converged iterate has it within some element's span
  // on the beam's other side, it went through: passed_through() must say so (before, only the
  // elements that held it at the release were checked, and a beam-on-beam run accepted a state
  // with the tip through the beam). Above the beam, or off its free end, it is fine.
  BeamSpec b;
  b.divisions = 10;
  const tsm::Model model = tsm::io::read_model(pusher_model(b, 0.35, 0.01, 0.0, -0.02, 1));
  tsm::contact::ContactSet tracker(model);
  std::vector<tsm::contact::ContactState> states = tracker.initial_states();
  states[0].active = true;
  states[0].element = 3;
  states[0].side = 1;
  const std::vector<double> rotations(model.elements.size(), 0.0);
  const tsm::contact::StepStart unloaded = tsm::contact::unloaded_start(model);  // the references' state
  const int pusher = model.node_index(100);
  const auto at = [&](double x, double y) {  // the pusher moved to (x, y), the beam straight
    Eigen::VectorXd D = Eigen::VectorXd::Zero(model.dof_count());
    D.segment<2>(3 * pusher) = Eigen::Vector2d(x - 0.35, y - 0.01);
    return D;
  };
  const Eigen::VectorXd wild = at(5.0, 3.0);
  // Y > 0 on side +1 is a pull (compression −side·Y); the iterate has converged.
  const tsm::contact::ContactChanges changes =
      tracker.update(wild, rotations, {tsm::contact::ContactEvaluation{0, false, 0.4, 10.0}}, states, true, unloaded);
  ASSERT_EQ(changes.released, 1);
  ASSERT_FALSE(states[0].active);
  EXPECT_TRUE(tracker.passed_through(at(0.75, -0.001), rotations, states));   // under element 7
  EXPECT_TRUE(tracker.passed_through(at(0.05, -0.2), rotations, states));     // under element 0
  EXPECT_FALSE(tracker.passed_through(at(0.75, 0.001), rotations, states));   // above
  EXPECT_FALSE(tracker.passed_through(at(1.2, -0.1), rotations, states));     // beyond the free end
}

TEST(ContactRelease, ANodeThatLetGoOfARingIsThroughItOnlyWhereItIsInside) {
  // A closed ring (radius 1, 120 elements) and a node above its top that lets go by pulling. The
  // side it pressed from, carried round the ring, is the wrong one for the elements at the
  // ring's bottom, whose span the node above the top also lies across: it was called "through"
  // the ring there, and a rope draped over a ring (I = 1e-10) never settled its contacts.
  // Only the element nearest across the node's position counts.
  const json m = {{"materials", {{"steel", {{"E", 2e11}}}}},
                  {"sections", {{"ring", {{"A", 1e-2}, {"I", 1e-4}}}}},
                  {"nodes", json::array({{{"id", 1}, {"x", 0.0}, {"y", -1.0}}, {{"id", 100}, {"x", 0.01}, {"y", 1.01}}})},
                  {"members", json::array({{{"from", 1}, {"to", 1}, {"arc", {{"center", {0.0, 0.0}}, {"sweep", 2.0 * std::numbers::pi}}},
                                            {"divisions", 120}, {"material", "steel"}, {"section", "ring"}}})},
                  {"supports", json::array({{{"node", 1}, {"type", "fixed"}}, {{"node", 100}, {"type", "fixed"}}})},
                  {"contacts", json::array({{{"node", 100}, {"members", {0}}}})},
                  {"analysis", {{"control", {{"type", "load"}, {"steps", 1}}}}}};
  const tsm::Model model = tsm::io::read_model(m);
  tsm::contact::ContactSet tracker(model);
  std::vector<tsm::contact::ContactState> states = tracker.initial_states();
  int top = -1;  // the element under the node
  for (size_t e = 0; e < model.elements.size(); ++e) {
    const Eigen::Vector2d a = model.nodes[model.elements[e].start].position, b = model.nodes[model.elements[e].end].position;
    if (a.y() > 0.9 && b.y() > 0.9 && std::min(a.x(), b.x()) <= 0.01 && std::max(a.x(), b.x()) >= 0.01) top = static_cast<int>(e);
  }
  ASSERT_GE(top, 0);
  const Eigen::Vector2d a = model.nodes[model.elements[top].start].position, b = model.nodes[model.elements[top].end].position;
  const Eigen::Vector2d n(-(b - a).y(), (b - a).x());
  const int side = n.dot(Eigen::Vector2d(0.01, 1.01) - a) > 0.0 ? 1 : -1;  // the node's side of the top element
  states[0].active = true;
  states[0].element = top;
  states[0].side = side;
  const std::vector<double> rotations(model.elements.size(), 0.0);
  const tsm::contact::StepStart unloaded = tsm::contact::unloaded_start(model);  // the references' state
  const int node = model.node_index(100);
  const auto at = [&](double x, double y) {  // the node moved to (x, y), the ring as drawn
    Eigen::VectorXd D = Eigen::VectorXd::Zero(model.dof_count());
    D.segment<2>(3 * node) = Eigen::Vector2d(x - 0.01, y - 1.01);
    return D;
  };
  const tsm::contact::ContactChanges changes =
      tracker.update(at(0.01, 1.005), rotations, {tsm::contact::ContactEvaluation{0, false, 0.5, side * 10.0}}, states, true, unloaded);
  ASSERT_EQ(changes.released, 1);
  EXPECT_FALSE(tracker.passed_through(at(0.01, 1.02), rotations, states));   // above the ring
  EXPECT_FALSE(tracker.passed_through(at(0.3, 1.2), rotations, states));     // above, further on
  EXPECT_TRUE(tracker.passed_through(at(0.01, 0.99), rotations, states));    // just inside, under the top
  EXPECT_TRUE(tracker.passed_through(at(0.0, 0.0), rotations, states));      // at the centre
}

}  // namespace
