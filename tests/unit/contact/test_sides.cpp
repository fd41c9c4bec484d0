// The sides a contact node is on, read and carried along the beam (contact/sides.hpp).
#include <gtest/gtest.h>

#include "support/contact_fixture.hpp"
#include "tsmframe/contact/sides.hpp"

namespace {

using tsm::contact::ContactGeometry;
using tsm::contact::ContactState;
using tsm::contact::no_side;
using tsm::test::ContactFixture;
using tsm::test::json;

ContactState sides_at(const ContactGeometry& geometry, const ContactFixture& f) { return tsm::test::reference_state(geometry, f); }

TEST(ContactSides, ANodeAboveTheBeamIsOnTheNormalsSideOfEveryElement) {
  ContactFixture f(0.3, 0.1);  // elements run left to right: n = +y
  const ContactGeometry geometry(f.model);
  const ContactState state = sides_at(geometry, f);
  EXPECT_EQ(state.reference.side.values(), (std::vector<signed char>{1, 1, 1, 1}));
  // Its place in each chord's frame and its position, for detection's swept crossing.
  EXPECT_NEAR(state.reference.along[1], 0.2, 1e-15);
  EXPECT_NEAR(state.reference.across[3], 0.1, 1e-15);
  EXPECT_EQ(state.reference.position[0], 0.3);
  EXPECT_EQ(state.reference.position[1], 0.1);
}

TEST(ContactSides, ANodeBelowTheBeamIsAgainstTheNormal) {
  ContactFixture f(0.6, -0.05);
  const ContactGeometry geometry(f.model);
  EXPECT_EQ(sides_at(geometry, f).reference.side.values(), (std::vector<signed char>{-1, -1, -1, -1}));
}

TEST(ContactSides, FarBeyondAnElementsReachTheSideIsCarriedAlongTheBeam) {
  // Eight elements of 0.125: the node over x = 0.06 is more than one element length beyond
  // elements 2–7 (α < −1), whose sides come from element 0 through the beam's nodes.
  ContactFixture f(0.06, 0.01, json::object(), 8);
  const ContactGeometry geometry(f.model);
  const ContactState state = sides_at(geometry, f);
  EXPECT_EQ(state.reference.side.values(), (std::vector<signed char>(8, 1)));
}

TEST(ContactSides, AStepsStartKeepsTheListedCandidatesSidesOnlyAndReadsEveryOtherWhenAskedTo) {
  // 400 elements of 2.5 mm, the node 1 cm above x = 0.5: a step's start keeps the sides of the
  // elements within the broad phase's radius of it only (0.0225 m: 18 of them) — a contact's
  // reference grows with what is near it, not with the candidates (10⁴ contact nodes on 3·10⁴
  // candidates were 3·10⁸ sides read at every step). Asked for every side (an iterate beyond the
  // list's reach), it holds what a reference of every candidate holds.
  ContactFixture f(0.5, 0.01, json::object(), 400);
  const ContactGeometry geometry(f.model);
  const tsm::contact::StepStart start = tsm::contact::step_start(f.D, f.rotations);
  tsm::contact::ChordFrames frames(geometry, f.D);
  ContactState state;
  tsm::contact::reset_near_sides(geometry, geometry.contact(0), start, tsm::contact::CandidateChords(geometry, f.D), frames, state);
  EXPECT_TRUE(state.reference.sides_of_near);
  EXPECT_EQ(state.reference.near.size(), 18u);
  EXPECT_EQ(state.reference.side.values(), (std::vector<signed char>(18, 1)));
  EXPECT_EQ(state.reference.side_of(0), no_side) << "not held";
  tsm::contact::take_every_side(geometry, geometry.contact(0), start, frames, state.reference);
  EXPECT_FALSE(state.reference.sides_of_near);
  EXPECT_EQ(state.reference.side.values(), sides_at(geometry, f).reference.side.values());
  EXPECT_EQ(state.reference.side.values(), (std::vector<signed char>(400, 1)));
}

TEST(ContactSides, ANodeOnTheCentreLineHasNoSideYet) {
  ContactFixture f(0.3, 0.0);
  const ContactGeometry geometry(f.model);
  const ContactState state = sides_at(geometry, f);
  EXPECT_EQ(state.reference.side[1], 0);  // the element under it
}

TEST(ContactSides, AcrossAMembersInteriorNodeTheSideGoesOnUnchanged) {
  ContactFixture f(0.3, 0.1);
  const ContactGeometry geometry(f.model);
  // From element 1 across its end node (x = 0.5) onto element 2, which starts there: same side.
  const int node = f.model.elements[1].end;
  EXPECT_EQ(tsm::contact::across(geometry, geometry.contact(0), 1, 1, node, f.D), (std::pair<int, int>{2, 1}));
  EXPECT_EQ(tsm::contact::across(geometry, geometry.contact(0), 1, -1, node, f.D), (std::pair<int, int>{2, -1}));
  // At the beam's free end there is nothing to go on with.
  EXPECT_EQ(tsm::contact::across(geometry, geometry.contact(0), 3, 1, f.model.elements[3].end, f.D),
            (std::pair<int, int>{-1, 0}));
}

TEST(ContactSides, AcrossElementsRunningAgainstEachOtherTheSideFlips) {
  // Two members meeting head to head at x = 0.5: the second runs from x = 1 back to 0.5, so its
  // normal points down where the first's points up — the same physical side is −1 on it.
  tsm::test::BeamSpec b;
  b.L = 0.5;
  b.divisions = 2;
  b.A = 1e3;
  json m = tsm::test::beam_model(b);
  m["nodes"].push_back({{"id", 3}, {"x", 1.0}, {"y", 0.0}});
  m["nodes"].push_back({{"id", 100}, {"x", 0.3}, {"y", 0.1}});
  m["nodes"].push_back({{"id", 11}, {"x", 0.3}, {"y", 0.6}});
  m["members"].push_back({{"from", 3}, {"to", 2}, {"divisions", 2}, {"material", "m"}, {"section", "s"}});
  m["members"].push_back({{"from", 11}, {"to", 100}, {"divisions", 1}, {"material", "m"}, {"section", "s"}});
  m["supports"] = json::array({{{"node", 1}, {"type", "fixed"}}, {{"node", 3}, {"type", "fixed"}}, {{"node", 11}, {"type", "fixed"}}});
  m["contacts"] = json::array({{{"node", 100}, {"members", {0, 1}}}});
  const tsm::Model model = tsm::io::read_model(m);
  const ContactGeometry geometry(model);
  const Eigen::VectorXd D = Eigen::VectorXd::Zero(model.dof_count());
  const int joint = model.node_index(2);
  // Element 1 (0.25 → 0.5) ends at the joint; element 3 (0.75 → 0.5) ends there too.
  ASSERT_EQ(model.elements[1].end, joint);
  ASSERT_EQ(model.elements[3].end, joint);
  EXPECT_EQ(tsm::contact::across(geometry, geometry.contact(0), 1, 1, joint, D), (std::pair<int, int>{3, -1}));
  ContactState state;
  state.reference.side.set(std::vector<signed char>(4, 0));
  const std::vector<double> rotations(model.elements.size(), 0.0);
  tsm::contact::reset_sides(geometry, geometry.contact(0), D, rotations, 0, state);
  EXPECT_EQ(state.reference.side.values(), (std::vector<signed char>{1, 1, -1, -1}));
}

TEST(ContactSides, AtAJointOfThreeTheSideGoesOnAcrossTheSectorItFaces) {
  // A beam along x with a column hanging below its middle node: the beam's top faces the sector
  // between its two halves (above), so from the left half's top it goes on to the right half's
  // top; the left half's underside faces the sector towards the column.
  tsm::test::BeamSpec b;
  b.divisions = 2;
  b.A = 1e3;
  json m = tsm::test::beam_model(b);
  m["nodes"].push_back({{"id", 4}, {"x", 0.5}, {"y", -0.5}});
  m["nodes"].push_back({{"id", 100}, {"x", 0.3}, {"y", 0.1}});
  m["nodes"].push_back({{"id", 11}, {"x", 0.3}, {"y", 0.6}});
  m["members"].push_back({{"from", 4}, {"to", {0.5, 0.0}}, {"divisions", 1}, {"material", "m"}, {"section", "s"}});
  m["members"].push_back({{"from", 11}, {"to", 100}, {"divisions", 1}, {"material", "m"}, {"section", "s"}});
  m["supports"] = json::array({{{"node", 1}, {"type", "fixed"}}, {{"node", 4}, {"type", "fixed"}}, {{"node", 11}, {"type", "fixed"}}});
  m["contacts"] = json::array({{{"node", 100}, {"members", {0, 1}}}});
  const tsm::Model model = tsm::io::read_model(m);
  const ContactGeometry geometry(model);
  const Eigen::VectorXd D = Eigen::VectorXd::Zero(model.dof_count());
  const int joint = model.elements[0].end, column = 2;
  ASSERT_EQ(model.elements[1].start, joint);
  ASSERT_EQ(model.elements[column].end, joint);  // the column runs up into the joint
  EXPECT_EQ(tsm::contact::across(geometry, geometry.contact(0), 0, 1, joint, D), (std::pair<int, int>{1, 1}));
  // The underside: on to the column, on the side facing the left half (the column runs up:
  // its normal points to −x, towards the left half: +1).
  EXPECT_EQ(tsm::contact::across(geometry, geometry.contact(0), 0, -1, joint, D), (std::pair<int, int>{column, 1}));
}

}  // namespace
