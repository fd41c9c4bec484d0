// A contact resting on a beam node between two elements (contact/vertex.hpp).
#include <gtest/gtest.h>

#include "support/contact_fixture.hpp"
#include "tsmframe/contact/sides.hpp"
#include "tsmframe/contact/sliding.hpp"
#include "tsmframe/contact/vertex.hpp"

namespace {

using tsm::contact::ContactGeometry;
using tsm::contact::ContactState;
using tsm::contact::Vertex;
using tsm::test::ContactFixture;

/// The fixture's node on the beam node at x = 0.5 (elements 1 and 2 meet there), as a vertex
/// reported on element 1 (which ends there), both sides pressed from above.
ContactState at_vertex(const ContactGeometry& geometry, const ContactFixture& f) {
  ContactState state = tsm::test::active_state(geometry, f, 1);
  state.alpha = 1.0;
  state.vertex = Vertex{2, 1, 0.0};
  return state;
}

TEST(ContactVertex, APointComingBackAcrossTheNodeItCameBackAcrossBeforeRestsOnIt) {
  // Sliding on (no reversal) never makes a vertex; nor the first time back across a node.
  ContactState state;
  state.step.handover_direction = 1;
  state.step.hop_node = 7;
  EXPECT_FALSE(tsm::contact::comes_to_rest_on_node(state, 1, 7, 0.01, 0.1, 0.1));   // sliding on
  EXPECT_FALSE(tsm::contact::comes_to_rest_on_node(state, -1, 5, 0.01, 0.1, 0.1));  // back across another node
  EXPECT_TRUE(tsm::contact::comes_to_rest_on_node(state, -1, 7, 0.01, 0.1, 0.1));
  EXPECT_FALSE(tsm::contact::comes_to_rest_on_node(state, -1, 7, 0.01, 0.6, 0.1));  // too far past the node
  EXPECT_FALSE(tsm::contact::comes_to_rest_on_node(state, -1, 7, 0.0, 0.1, 0.1));   // no edge: the law is singular there
  state.step.held_node = 7;  // a vertex opened here in this step: it stays open
  EXPECT_FALSE(tsm::contact::comes_to_rest_on_node(state, -1, 7, 0.01, 0.1, 0.1));
}

TEST(ContactVertex, AVertexIsReportedOnTheElementEndingAtTheNodeAtItsEnd) {
  ContactFixture f(0.5, 0.0);
  const int node = f.model.elements[1].end;
  ContactState state;
  state.active = true;
  state.element = 2;  // arriving from element 2, which starts at the node …
  state.side = 1;
  tsm::contact::enter_vertex(f.model, node, 1, -1, state);  // … onto element 1, which ends there
  EXPECT_EQ(state.element, 1);
  EXPECT_EQ(state.side, -1);
  ASSERT_TRUE(state.vertex);
  EXPECT_EQ(state.vertex->element, 2);
  EXPECT_EQ(state.vertex->side, 1);
  EXPECT_EQ(state.alpha, 1.0);
  EXPECT_EQ(tsm::contact::vertex_node(f.model, state), node);
}

TEST(ContactVertex, ItsForceIsTheCompressionOfBothElementsResultant) {
  // The beam kinked at x = 0.5 (v = a x²): the chords' normals meet at an angle, and the
  // reported force is the length of both elements' pushes, Y₁ n₁ + Y₂ n₂ (along the chords'
  // normals; the bent beam's are the elements' to give), signed by the compression −Σ side·Y.
  ContactFixture f(0.5, 0.0);
  f.bend_beam(0.4);
  const ContactGeometry geometry(f.model);
  ContactState state = at_vertex(geometry, f);
  state.Y = -3.0;  // side +1: compression 3
  const Eigen::Vector2d n1 = geometry.chord_normal(1, f.D, f.rotations), n2 = geometry.chord_normal(2, f.D, f.rotations);
  state.push[0] = -3.0 * n1.x();
  state.push[1] = -3.0 * n1.y();
  tsm::contact::read_vertex(f.model, -2.0, -2.0 * n2, state);
  EXPECT_NEAR(state.force, (-3.0 * n1 - 2.0 * n2).norm(), 1e-14);
  EXPECT_NEAR(state.push[0], (-3.0 * n1 - 2.0 * n2).x(), 1e-15);
  EXPECT_LT(state.force, 5.0);  // less than the sum: the normals differ
  EXPECT_EQ(state.vertex->Y, -2.0);
  EXPECT_EQ(state.alpha, 1.0);
}

TEST(ContactVertex, AtAConvergedIterateThePullingSideLetsGoAndBothPullingRelease) {
  ContactFixture f(0.5, 0.0);
  const ContactGeometry geometry(f.model);
  const int node = f.model.elements[1].end;
  tsm::contact::Occupancy occupied(f.model.elements.size());
  const auto open = [&](double Y1, double Y2, ContactState& state) {
    state.Y = Y1;
    state.vertex->Y = Y2;
    occupied = tsm::contact::Occupancy(f.model.elements.size());
    occupied.join(1, tsm::ContactFrame::chord);
    occupied.join(2, tsm::ContactFrame::chord);
    return tsm::contact::open_vertex(geometry, geometry.contact(0), f.D, f.rotations, state, occupied);
  };
  {  // both press (side +1: Y < 0): it stays
    ContactState state = at_vertex(geometry, f);
    EXPECT_FALSE(open(-3.0, -2.0, state));
    EXPECT_TRUE(state.vertex);
  }
  {  // element 2's side pulls: element 1 carries on, held at the node
    ContactState state = at_vertex(geometry, f);
    EXPECT_TRUE(open(-3.0, 2.0, state));
    EXPECT_FALSE(state.vertex);
    EXPECT_EQ(state.element, 1);
    EXPECT_EQ(state.step.held_node, node);
    EXPECT_EQ(state.force, 3.0);
    EXPECT_EQ(occupied.points(2), 0);
  }
  {  // element 1's side pulls: element 2 carries on
    ContactState state = at_vertex(geometry, f);
    EXPECT_TRUE(open(3.0, -2.0, state));
    EXPECT_EQ(state.element, 2);
    EXPECT_EQ(state.Y, -2.0);
    EXPECT_EQ(occupied.points(1), 0);
  }
  {  // both pull: released
    ContactState state = at_vertex(geometry, f);
    EXPECT_TRUE(open(3.0, 2.0, state));
    EXPECT_FALSE(state.active);
    EXPECT_FALSE(state.vertex);
    EXPECT_TRUE(state.step.released);
  }
}

TEST(ContactVertex, APointHoppingBackAndForthAcrossANodeComesToRestThere) {
  // Over element 1 to 2, back to 1 (a reversal at x = 0.5), and on to 2 again: the second time
  // back across the node it rests on both elements.
  ContactFixture f(0.45, 0.0);
  const ContactGeometry geometry(f.model);
  ContactState state = tsm::test::active_state(geometry, f, 1);
  tsm::contact::Occupancy occupied(f.model.elements.size());
  occupied.join(1, tsm::ContactFrame::chord);
  for (const double x : {0.52, 0.48, 0.52}) {
    f.move_foot(x - 0.45, 0.0);
    state.alpha = geometry.locate(geometry.contact(0), state.element, f.D, f.rotations).alpha;
    tsm::contact::hand_over(geometry, geometry.contact(0), f.D, f.rotations, false, state, occupied);
  }
  ASSERT_TRUE(state.vertex);
  EXPECT_EQ(state.element, 1);  // reported on the element ending at the node
  EXPECT_EQ(state.vertex->element, 2);
  EXPECT_EQ(occupied.points(1), 1);
  EXPECT_EQ(occupied.points(2), 1);
  EXPECT_TRUE(occupied.may_join(1, tsm::ContactFrame::chord));  // a point of each element: others may join (issue 27)
  EXPECT_TRUE(occupied.may_join(2, tsm::ContactFrame::chord));
}

}  // namespace
