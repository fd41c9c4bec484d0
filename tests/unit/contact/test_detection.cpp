// Where a contact starts (contact/detection.hpp).
#include <gtest/gtest.h>

#include "support/contact_fixture.hpp"
#include "tsmframe/contact/detection.hpp"
#include "tsmframe/contact/sides.hpp"

namespace {

using tsm::contact::ChordFrames;
using tsm::contact::ContactGeometry;
using tsm::contact::ContactState;
using tsm::test::ContactFixture;

/// The contact's state at the fixture as drawn (its reference sides read there).
ContactState drawn(const ContactGeometry& geometry, const ContactFixture& f) { return tsm::test::reference_state(geometry, f); }

std::optional<tsm::contact::HandOver> detect(const ContactGeometry& geometry, const ContactFixture& f,
                                             ContactState& state, tsm::contact::Occupancy& occupied) {
  ChordFrames frames(geometry, f.D);
  return tsm::contact::detect(geometry, geometry.contact(0), f.D, f.rotations, frames, state, occupied);
}

TEST(ContactDetection, ANodeThatReachesTheBeamFromAboveTouchesTheElementUnderIt) {
  ContactFixture f(0.3, 0.1);
  const ContactGeometry geometry(f.model);
  ContactState state = drawn(geometry, f);
  tsm::contact::Occupancy occupied(f.model.elements.size());
  f.move_foot(0.0, -0.09);  // still 1 cm above: nothing
  EXPECT_FALSE(detect(geometry, f, state, occupied));
  EXPECT_FALSE(state.active);
  f.move_foot(0.0, -0.1001);  // just through the centre line
  ASSERT_TRUE(detect(geometry, f, state, occupied));
  EXPECT_TRUE(state.active);
  EXPECT_EQ(state.element, 1);
  EXPECT_EQ(state.side, 1);  // it presses from above
  EXPECT_NEAR(state.alpha, 0.2, 1e-12);
  EXPECT_EQ(state.Y, 0.0);  // a contact starts without a jump
  EXPECT_EQ(occupied.points(1), 1);
}

TEST(ContactDetection, AContactWithAGapStartsAtTheGap) {
  ContactFixture f(0.3, 0.1, {{"gap", 0.02}});
  const ContactGeometry geometry(f.model);
  ContactState state = drawn(geometry, f);
  tsm::contact::Occupancy occupied(f.model.elements.size());
  f.move_foot(0.0, -0.079);  // 2.1 cm above
  EXPECT_FALSE(detect(geometry, f, state, occupied));
  f.move_foot(0.0, -0.081);  // 1.9 cm above: within the gap
  ASSERT_TRUE(detect(geometry, f, state, occupied));
  EXPECT_EQ(state.side, 1);
}

TEST(ContactDetection, ANodeOffTheCentreLineItStartedOnPushesTheWayItMoves) {
  ContactFixture f(0.3, 0.0);  // drawn on the centre line: no side yet
  const ContactGeometry geometry(f.model);
  ContactState state = drawn(geometry, f);
  tsm::contact::Occupancy occupied(f.model.elements.size());
  f.move_foot(0.0, 1e-12);  // within the tolerance (1e-10 × size): still on it
  EXPECT_FALSE(detect(geometry, f, state, occupied));
  f.move_foot(0.0, -1e-3);
  ASSERT_TRUE(detect(geometry, f, state, occupied));
  EXPECT_EQ(state.side, 1);  // moved down: it presses down, as from above
}

TEST(ContactDetection, AnElementAPointOfTheOtherFrameIsOnBlocksTheNodeAndSaysWhich) {
  ContactFixture f(0.3, 0.1);
  const ContactGeometry geometry(f.model);
  ContactState state = drawn(geometry, f);
  tsm::contact::Occupancy occupied(f.model.elements.size());
  occupied.join(1, tsm::ContactFrame::cantilever);  // a point of the other frame
  f.move_foot(0.0, -0.11);
  EXPECT_FALSE(detect(geometry, f, state, occupied));
  EXPECT_EQ(state.step.blocked_element, 1);
}

TEST(ContactDetection, ANodeReachingAnElementAnotherPointIsOnJoinsIt) {
  // Issue 27: an element carries any number of points of one frame.
  ContactFixture f(0.3, 0.1);
  const ContactGeometry geometry(f.model);
  ContactState state = drawn(geometry, f);
  tsm::contact::Occupancy occupied(f.model.elements.size());
  occupied.join(1, tsm::ContactFrame::chord);
  f.move_foot(0.0, -0.11);
  ASSERT_TRUE(detect(geometry, f, state, occupied));
  EXPECT_EQ(state.element, 1);
  EXPECT_EQ(state.step.blocked_element, -1);
  EXPECT_EQ(occupied.points(1), 2);
}

TEST(ContactDetection, AContactReleasedInTheStepDoesNotTouchAgainWithinIt) {
  ContactFixture f(0.3, 0.1);
  const ContactGeometry geometry(f.model);
  ContactState state = drawn(geometry, f);
  state.step.released = true;
  tsm::contact::Occupancy occupied(f.model.elements.size());
  f.move_foot(0.0, -0.11);
  EXPECT_FALSE(detect(geometry, f, state, occupied));
}

TEST(ContactDetection, ANodeThatCrossedASpanAndWentOnBeyondStartsOnItAndIsHandedOn) {
  // From above x = 0.3 to (1.3, −0.2), past the free end, in one iterate: within no element's
  // span now, but its path crossed the centre line at x = 0.3 + 1/3 (0.1 down of its 0.3 fall),
  // over element 2. Contact starts there and is handed on along the beam towards the node — one
  // element per iterate here, as 5 % of the model's size (0.058) is less than an element.
  ContactFixture f(0.3, 0.1);
  const ContactGeometry geometry(f.model);
  ContactState state = drawn(geometry, f);
  tsm::contact::Occupancy occupied(f.model.elements.size());
  f.move_foot(1.0, -0.3);
  EXPECT_EQ(tsm::contact::swept_crossing(geometry, geometry.contact(0), state, f.D, occupied), 2);
  const auto handed = detect(geometry, f, state, occupied);
  ASSERT_TRUE(handed);
  EXPECT_TRUE(state.active);
  EXPECT_EQ(handed->handed_over, 1);
  EXPECT_EQ(state.element, 3);
  EXPECT_NEAR(state.alpha, (1.3 - 0.75) / 0.25, 1e-12);  // held beyond the free end until a converged iterate
}

}  // namespace
