// A contact point handed on through element ends (contact/sliding.hpp).
#include <gtest/gtest.h>

#include <algorithm>

#include "support/contact_fixture.hpp"
#include "tsmframe/contact/sides.hpp"
#include "tsmframe/contact/sliding.hpp"

namespace {

using tsm::contact::ContactGeometry;
using tsm::contact::ContactState;
using tsm::contact::Occupancy;
using tsm::contact::HandOver;
using tsm::test::ContactFixture;

/// The contact active on `element` from above, its node at the fixture's displacements.
ContactState on(const ContactGeometry& geometry, const ContactFixture& f, int element, Occupancy& occupied) {
  const ContactState state = tsm::test::active_state(geometry, f, element);
  occupied = Occupancy(f.model.elements.size());
  occupied.join(element, tsm::ContactFrame::chord);
  return state;
}

TEST(ContactSliding, APointPastAnElementsEndGoesOnToTheNextElement) {
  ContactFixture f(0.3, 0.0);
  const ContactGeometry geometry(f.model);
  Occupancy occupied(0);
  ContactState state = on(geometry, f, 1, occupied);
  f.move_foot(0.25, 0.0);  // to x = 0.55: α = 1.2 on element 1
  state.alpha = geometry.locate(geometry.contact(0), 1, f.D, f.rotations).alpha;
  const HandOver h = tsm::contact::hand_over(geometry, geometry.contact(0), f.D, f.rotations, false, state, occupied);
  EXPECT_EQ(h.handed_over, 1);
  EXPECT_EQ(h.reversed, 0);
  EXPECT_EQ(state.element, 2);
  EXPECT_NEAR(state.alpha, 0.2, 1e-12);
  EXPECT_EQ(state.side, 1);
  EXPECT_EQ(state.step.handover_direction, 1);
  EXPECT_EQ(occupied.points(1), 0);
  EXPECT_EQ(occupied.points(2), 1);
}

TEST(ContactSliding, APointGoesNoFartherThanOneElementOrAFewPerCentOfTheModelPerIterate) {
  // 5 % of the model's size (its bounding box's diagonal, 1.166 here) is less than an element
  // (0.25): one element per iterate, the point left beyond it for the next.
  ContactFixture f(0.1, 0.0);
  const ContactGeometry geometry(f.model);
  Occupancy occupied(0);
  ContactState state = on(geometry, f, 0, occupied);
  f.move_foot(0.6, 0.0);  // to x = 0.7: α = 2.8 on element 0
  state.alpha = geometry.locate(geometry.contact(0), 0, f.D, f.rotations).alpha;
  const HandOver h = tsm::contact::hand_over(geometry, geometry.contact(0), f.D, f.rotations, false, state, occupied);
  EXPECT_EQ(h.handed_over, 1);
  EXPECT_EQ(state.element, 1);
  EXPECT_NEAR(state.alpha, 1.8, 1e-12);
}

TEST(ContactSliding, AtAFreeEndThePointIsHeldUntilAConvergedIterateLetsItGo) {
  ContactFixture f(0.9, 0.0);
  const ContactGeometry geometry(f.model);
  Occupancy occupied(0);
  ContactState state = on(geometry, f, 3, occupied);
  f.move_foot(0.2, 0.0);  // to x = 1.1: past the free end
  state.alpha = geometry.locate(geometry.contact(0), 3, f.D, f.rotations).alpha;
  HandOver h = tsm::contact::hand_over(geometry, geometry.contact(0), f.D, f.rotations, false, state, occupied);
  EXPECT_FALSE(h.released);
  EXPECT_TRUE(state.active);  // the force still acts at the end
  EXPECT_EQ(state.element, 3);
  h = tsm::contact::hand_over(geometry, geometry.contact(0), f.D, f.rotations, true, state, occupied);
  EXPECT_TRUE(h.released);
  EXPECT_FALSE(state.active);
  EXPECT_EQ(state.step.slid_off_element, 3);
  EXPECT_TRUE(state.step.released);
  EXPECT_EQ(occupied.points(3), 0);
}

TEST(ContactSliding, AnElementAPointOfTheOtherFrameIsOnStopsThePointAsAFreeEndWould) {
  ContactFixture f(0.3, 0.0);
  const ContactGeometry geometry(f.model);
  Occupancy occupied(0);
  ContactState state = on(geometry, f, 1, occupied);
  occupied.join(2, tsm::ContactFrame::cantilever);  // a point of the other frame
  f.move_foot(0.25, 0.0);
  state.alpha = geometry.locate(geometry.contact(0), 1, f.D, f.rotations).alpha;
  const HandOver h = tsm::contact::hand_over(geometry, geometry.contact(0), f.D, f.rotations, false, state, occupied);
  EXPECT_EQ(h.handed_over, 0);
  EXPECT_EQ(state.element, 1);
}

TEST(ContactSliding, APointPassesOntoAnElementAnotherPointIsOn) {
  // Issue 27: an element carries any number of points of one frame.
  ContactFixture f(0.3, 0.0);
  const ContactGeometry geometry(f.model);
  Occupancy occupied(0);
  ContactState state = on(geometry, f, 1, occupied);
  occupied.join(2, tsm::ContactFrame::chord);  // another contact's point
  f.move_foot(0.25, 0.0);
  state.alpha = geometry.locate(geometry.contact(0), 1, f.D, f.rotations).alpha;
  const HandOver h = tsm::contact::hand_over(geometry, geometry.contact(0), f.D, f.rotations, false, state, occupied);
  EXPECT_EQ(h.handed_over, 1);
  EXPECT_EQ(state.element, 2);
  EXPECT_EQ(occupied.points(1), 0);
  EXPECT_EQ(occupied.points(2), 2);
}

TEST(ContactSliding, APointComingBackTheWayItWentCountsAReversalAtThatNode) {
  ContactFixture f(0.3, 0.0);
  const ContactGeometry geometry(f.model);
  Occupancy occupied(0);
  ContactState state = on(geometry, f, 1, occupied);
  f.move_foot(0.25, 0.0);  // on to element 2
  state.alpha = geometry.locate(geometry.contact(0), 1, f.D, f.rotations).alpha;
  tsm::contact::hand_over(geometry, geometry.contact(0), f.D, f.rotations, false, state, occupied);
  ASSERT_EQ(state.element, 2);
  f.move_foot(0.15, 0.0);  // back to x = 0.45: α = −0.2 on element 2
  state.alpha = geometry.locate(geometry.contact(0), 2, f.D, f.rotations).alpha;
  const HandOver h = tsm::contact::hand_over(geometry, geometry.contact(0), f.D, f.rotations, false, state, occupied);
  EXPECT_EQ(h.reversed, 1);
  EXPECT_EQ(state.element, 1);
  EXPECT_EQ(state.step.hop_node, f.model.elements[1].end);
  EXPECT_EQ(state.step.handover_direction, -1);
}

TEST(ContactSliding, APointBeyondBothElementsOfAPeakIsHandedOverNoMoreTimesThanThereAreElements) {
  // The beam's middle node lifted 0.5 into a peak, the post's foot 10 above it: beyond the end of
  // element 1 (α = 17) and before the start of element 2 (α = −16), so each hands the point back
  // to the other. The post drawn 1,000 up makes the model's size ~1,000, and 5 % of it is 200
  // elements' lengths: the point went to and fro 200 times per iterate (a fuzzed model with a node
  // at y = 10⁹ took minutes) — now at most once per element of the model.
  ContactFixture f(0.5, 1000.0);
  const ContactGeometry geometry(f.model);
  f.D.segment<2>(tsm::dofs_per_node * f.model.elements[1].end) << 0.0, 0.5;
  f.move_foot(0.0, 10.5 - 1000.0);
  Occupancy occupied(0);
  ContactState state = on(geometry, f, 1, occupied);
  ASSERT_NEAR(state.alpha, 17.0, 1e-9);
  ASSERT_NEAR(geometry.locate(geometry.contact(0), 2, f.D, f.rotations).alpha, -16.0, 1e-9);
  const HandOver h = tsm::contact::hand_over(geometry, geometry.contact(0), f.D, f.rotations, false, state, occupied);
  EXPECT_GE(h.handed_over, 1);
  EXPECT_LE(h.handed_over, static_cast<int>(f.model.elements.size()));
  EXPECT_TRUE(state.element == 1 || state.element == 2) << state.element;
  int holding = 0;  // still one element holds it
  for (int e = 0; e < static_cast<int>(f.model.elements.size()); ++e) holding += occupied.points(e);
  EXPECT_EQ(holding, 1);
}

}  // namespace
