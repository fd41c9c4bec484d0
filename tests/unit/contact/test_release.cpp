// A contact letting go, and the node that may not pass through the beam after it (contact/release.hpp).
#include <gtest/gtest.h>

#include "support/contact_fixture.hpp"
#include "tsmframe/contact/release.hpp"
#include "tsmframe/contact/sides.hpp"

namespace {

using tsm::contact::ContactGeometry;
using tsm::contact::ContactState;
using tsm::contact::no_side;
using tsm::test::ContactFixture;

/// The fixture's node pressing element `element` from above, on the centre line.
ContactState pressing(const ContactGeometry& geometry, const ContactFixture& f, int element) {
  ContactState state = tsm::test::active_state(geometry, f, element);
  state.Y = 5.0;  // pulling (side +1: compression −Y)
  state.force = -5.0;
  return state;
}

TEST(ContactRelease, ALetGoByPullingRemembersItsSideAlongTheWholeBeam) {
  ContactFixture f(0.3, 0.0);
  const ContactGeometry geometry(f.model);
  ContactState state = pressing(geometry, f, 1);
  tsm::contact::release(geometry, geometry.contact(0), f.D, f.rotations, state, true);
  EXPECT_FALSE(state.active);
  EXPECT_EQ(state.element, -1);
  EXPECT_EQ(state.force, 0.0);
  EXPECT_TRUE(state.step.released);
  EXPECT_TRUE(state.step.released_pulled);
  EXPECT_EQ(state.step.slid_off_element, -1);
  EXPECT_EQ(state.step.released_side, 1);
  EXPECT_EQ(state.step.released_normal[1], 1.0);
  // The side it let go on, carried from element 1 to every element of the beam.
  EXPECT_EQ(state.reference.side.values(), (std::vector<signed char>{1, 1, 1, 1}));
  // Within the span of element 1, and its neighbours across its nodes.
  EXPECT_EQ(state.step.released_within, (std::vector<int>{0, 1, 2}));
}

TEST(ContactRelease, ALetGoOffAFreeEndNamesTheElementItLeft) {
  ContactFixture f(1.05, 0.0);
  const ContactGeometry geometry(f.model);
  ContactState state = pressing(geometry, f, 3);
  tsm::contact::release(geometry, geometry.contact(0), f.D, f.rotations, state, false);
  EXPECT_EQ(state.step.slid_off_element, 3);
  EXPECT_FALSE(state.step.released_pulled);
}

TEST(ContactRelease, ANodeLetGoOffAnEndKeepsItsPlaceThenAndAConvergedStateFreesIt) {
  // A reference taken at a step's start reads the node's place in each chord's frame from the
  // step start's displacements (detection.hpp, swept_crossing): one byte per candidate, its side.
  // One taken at a release, away from the step's start, keeps the place it was taken at.
  ContactFixture f(1.05, 0.0);
  const ContactGeometry geometry(f.model);
  ContactState state = pressing(geometry, f, 3);
  tsm::contact::release(geometry, geometry.contact(0), f.D, f.rotations, state, false);
  ASSERT_EQ(state.reference.along.size(), 4u);
  EXPECT_NEAR(state.reference.along[3], (1.05 - 0.75) / 0.25, 1e-12);
  EXPECT_NEAR(state.reference.across[3], 0.0, 1e-15);
  tsm::contact::reset_sides(geometry, geometry.contact(0), f.D, f.rotations, 0, state);  // as at a converged state
  EXPECT_EQ(state.reference.side.size(), 4u);
  EXPECT_EQ(state.reference.along.capacity(), 0u);
  EXPECT_EQ(state.reference.across.capacity(), 0u);
}

/// The fixture's contact, pressing element 1, let go by pulling; through(dx, dy): whether its
/// node, moved by (dx, dy) from where it was drawn, has passed through the beam since.
struct LetGo {
  ContactFixture& f;
  const ContactGeometry geometry{f.model};
  ContactState state = pressing(geometry, f, 1);
  explicit LetGo(ContactFixture& fixture) : f(fixture) {
    tsm::contact::release(geometry, geometry.contact(0), f.D, f.rotations, state, true);
  }
  bool through(double dx, double dy) {
    f.move_foot(dx, dy);
    return tsm::contact::passed_through(geometry, geometry.contact(0), f.D, f.rotations, state, tsm::contact::ElementLoads({state}));
  }
};

TEST(ContactRelease, AfterLettingGoTheNodeMayNotPassThroughTheBeam) {
  ContactFixture f(0.3, 0.0);
  LetGo let_go(f);
  const auto through = [&](double dx, double dy) { return let_go.through(dx, dy); };
  EXPECT_FALSE(through(0.0, 0.01));   // above, where it let go
  EXPECT_TRUE(through(0.0, -0.01));   // below element 1
  EXPECT_TRUE(through(0.5, -0.01));   // below element 3: the side holds along the whole beam
  EXPECT_FALSE(through(0.9, -0.01));  // beyond the free end: no beam to be through
}

TEST(ContactRelease, ANodeThatSinksWithinItsGapHasPassedThroughAsDetectionHasIt) {
  // A contact 5 cm off the centre line, let go where it touched: the node may come back to the
  // 5 cm line but no closer — closer, detection would have it in touch, so a converged iterate
  // with it there has gone through the beam's offset surface (on the element it let go of, and
  // on one beyond the elements that held it).
  ContactFixture f(0.3, 0.05, {{"gap", 0.05}});
  LetGo let_go(f);
  const auto through = [&](double dx, double dy) { return let_go.through(dx, dy); };
  EXPECT_FALSE(through(0.0, 0.0));     // on the 5 cm line, where it let go
  EXPECT_FALSE(through(0.0, 0.001));   // lifted off
  EXPECT_TRUE(through(0.0, -0.001));   // 1 mm into the gap, still 4.9 cm above the centre line
  EXPECT_TRUE(through(0.5, -0.02));    // 2 cm into it above element 3, beyond those that held it
  EXPECT_FALSE(through(0.5, 0.001));
}

TEST(ContactRelease, OffAFreeEndTheNodeMayGoRoundIt) {
  ContactFixture f(0.95, 0.0);
  const ContactGeometry geometry(f.model);
  ContactState state = pressing(geometry, f, 3);
  f.move_foot(0.1, 0.0);  // past the end
  tsm::contact::release(geometry, geometry.contact(0), f.D, f.rotations, state, false);
  f.move_foot(0.1, -0.05);  // under the beam's end, beyond its span: round the end, not through
  EXPECT_FALSE(tsm::contact::passed_through(geometry, geometry.contact(0), f.D, f.rotations, state, tsm::contact::ElementLoads({state})));
}

TEST(ContactRelease, ANodeNotReleasedInTheStepIsNeverThrough) {
  ContactFixture f(0.3, -0.01);
  const ContactGeometry geometry(f.model);
  const ContactState state = tsm::test::reference_state(geometry, f);
  EXPECT_FALSE(tsm::contact::passed_through(geometry, geometry.contact(0), f.D, f.rotations, state, tsm::contact::ElementLoads({state})));
}

}  // namespace
