// Newton's step cut short where contacts land (contact/landing.hpp): the fraction of a step that
// leaves an inactive contact's node no deeper than two of its candidate's element lengths beyond
// the gap (landing_depth_in_elements, 2), from the distances across the chords before and after
// the step; and a node it left through a beam's surface put back on it (landing_move).
#include <gtest/gtest.h>

#include "support/contact_fixture.hpp"
#include "tsmframe/contact/broad_phase.hpp"
#include "tsmframe/contact/landing.hpp"

namespace test_landing {
namespace {

using tsm::contact::ContactGeometry;
using tsm::contact::ContactState;
using tsm::contact::landing_depth_in_elements;
using tsm::contact::landing_fraction;
using tsm::contact::landing_move;
using tsm::contact::LandingMove;
using tsm::test::ContactFixture;

// A node 10 cm above a 1-m beam of 40 elements (2.5 cm), its contact's gap 5 mm: the surface is
// 5 mm above the axis and the node may land 2 × 2.5 cm = 5 cm beyond it, to y = −0.045.
constexpr double gap = 0.005, height = 0.1, element_length = 0.025;
const double deepest = gap - landing_depth_in_elements * element_length;

TEST(Landing, AStepThroughTheBeamIsCutToTheDepthAllowed) {
  ContactFixture f(0.5, height, {{"gap", gap}}, 40);
  const ContactGeometry geometry(f.model);
  const ContactState state = tsm::test::reference_state(geometry, f);
  Eigen::VectorXd trial = f.D;
  trial[tsm::dofs_per_node * f.foot + 1] = -0.3;  // to y = −0.2
  const double expected = (height - deepest) / (height - (-0.2));
  EXPECT_NEAR(landing_fraction(geometry, geometry.contact(0), state, f.D, trial), expected, 1e-12);
  // The same with the broad phase's list at the step's start.
  ContactState listed = state;
  tsm::contact::list_near_candidates(geometry, geometry.contact(0), f.D, tsm::contact::displacement_stamp(f.D),
                                     tsm::contact::CandidateChords(geometry, f.D), listed.reference);
  EXPECT_NEAR(landing_fraction(geometry, geometry.contact(0), listed, f.D, trial), expected, 1e-12);
}

TEST(Landing, TheBeamRisingToTheNodeIsCutAlike) {
  // Distances across the chord: the beam moving up 0.3 m is the node moving down 0.3 m.
  ContactFixture f(0.5, height, {{"gap", gap}}, 40);
  const ContactGeometry geometry(f.model);
  const ContactState state = tsm::test::reference_state(geometry, f);
  ContactFixture lifted = f;
  for (int k = 0; k < f.model.node_count(); ++k)
    if (k != f.foot && f.model.nodes[k].id != 11) lifted.D[tsm::dofs_per_node * k + 1] = 0.3;
  const double expected = (height - deepest) / (height - (-0.2));
  EXPECT_NEAR(landing_fraction(geometry, geometry.contact(0), state, f.D, lifted.D), expected, 1e-12);
}

TEST(Landing, ShallowLandingsStepsAwayAndPathsBesideTheSpanAreNotCut) {
  ContactFixture f(0.5, height, {{"gap", gap}}, 40);
  const ContactGeometry geometry(f.model);
  const ContactState state = tsm::test::reference_state(geometry, f);
  const auto fraction_to = [&](double dx, double dy) {
    Eigen::VectorXd trial = f.D;
    trial.segment<2>(tsm::dofs_per_node * f.foot) << dx, dy;
    return landing_fraction(geometry, geometry.contact(0), state, f.D, trial);
  };
  EXPECT_EQ(fraction_to(0.0, -0.14), 1.0);  // to y = −0.04, above the deepest −0.045
  EXPECT_LT(fraction_to(0.0, -0.15), 1.0);  // to y = −0.05
  EXPECT_EQ(fraction_to(0.0, 0.5), 1.0);    // away from the beam
  EXPECT_EQ(fraction_to(3.0, -0.3), 1.0);   // across y = 0.005 at x = 1.45, past the beam's end
}

TEST(Landing, AContactInTouchOrReleasedInTheStepIsNotCut) {
  ContactFixture f(0.5, height, {{"gap", gap}}, 40);
  const ContactGeometry geometry(f.model);
  Eigen::VectorXd trial = f.D;
  trial[tsm::dofs_per_node * f.foot + 1] = -0.3;
  const ContactState active = tsm::test::active_state(geometry, f, 20);
  EXPECT_EQ(landing_fraction(geometry, geometry.contact(0), active, f.D, trial), 1.0);
  ContactState released = tsm::test::reference_state(geometry, f);
  released.step.released = true;
  EXPECT_EQ(landing_fraction(geometry, geometry.contact(0), released, f.D, trial), 1.0);
}

TEST(Landing, ANodeThatLandedIsPutBackOnTheSurfaceAlongItsChordsNormal) {
  // The beam bent (v = 0.2 x²: element 20's chord tilted by ~0.2), the node 3 cm through its
  // surface: the move runs along that chord's normal and ends at the gap, α unchanged.
  ContactFixture f(0.51, height, {{"gap", gap}}, 40);
  f.bend_beam(0.2);
  f.move_foot(0.0, 0.2 * 0.51 * 0.51 - 0.03 - height);
  const ContactGeometry geometry(f.model);
  const int element = 20;  // [0.5, 0.525]
  const ContactState state = tsm::test::active_state(geometry, f, element);
  const tsm::contact::NodeOnElement before = geometry.locate(geometry.contact(0), element, f.D, f.rotations);
  ASSERT_LT(before.gap, -0.02);
  const LandingMove move = landing_move(geometry, geometry.contact(0), state, f.D, f.rotations);
  ASSERT_EQ(move.node, f.foot);
  const Eigen::Vector2d n = geometry.chord_normal(element, f.D, f.rotations);
  EXPECT_NEAR(move.by.normalized().dot(n), 1.0, 1e-12);
  EXPECT_GT(std::abs(n.x()), 0.1);  // a tilted normal
  Eigen::VectorXd moved = f.D;
  moved.segment<2>(tsm::dofs_per_node * f.foot) += move.by;
  const tsm::contact::NodeOnElement after = geometry.locate(geometry.contact(0), element, moved, f.rotations);
  EXPECT_NEAR(after.gap, gap, 1e-12);
  EXPECT_NEAR(after.alpha, before.alpha, 1e-12);
}

TEST(Landing, ANodeShortOfTheSurfaceAVertexAndAContactNotInTouchStayWhereTheyAre) {
  ContactFixture f(0.51, height, {{"gap", gap}}, 40);
  const ContactGeometry geometry(f.model);
  f.move_foot(0.0, 1.5 * gap - height);  // 2.5 mm short of the surface: not through it
  EXPECT_EQ(landing_move(geometry, geometry.contact(0), tsm::test::active_state(geometry, f, 20), f.D, f.rotations).node, -1);
  f.move_foot(0.0, -0.03 - height);  // through, but …
  ContactState vertex = tsm::test::active_state(geometry, f, 20);
  vertex.vertex.emplace();  // … resting on a node between two elements
  EXPECT_EQ(landing_move(geometry, geometry.contact(0), vertex, f.D, f.rotations).node, -1);
  const ContactState away = tsm::test::reference_state(geometry, f);  // not in touch
  EXPECT_EQ(landing_move(geometry, geometry.contact(0), away, f.D, f.rotations).node, -1);
  EXPECT_EQ(landing_move(geometry, geometry.contact(0), tsm::test::active_state(geometry, f, 20), f.D, f.rotations).node, f.foot);
}

}  // namespace
}  // namespace test_landing
