// Detection's broad phase (contact/broad_phase.hpp): the candidates a node can reach within a
// step, and detection over them finding what detection over every candidate finds.
#include <gtest/gtest.h>

#include <random>

#include "support/contact_fixture.hpp"
#include "tsmframe/contact/broad_phase.hpp"
#include "tsmframe/contact/detection.hpp"
#include "tsmframe/contact/sides.hpp"

namespace {

using tsm::contact::BroadPhase;
using tsm::contact::ContactGeometry;
using tsm::contact::ContactState;
using tsm::contact::StepStart;
using tsm::test::ContactFixture;

/// The fixture's contact as at a step's start at the fixture's displacements: sides read and
/// its near candidates listed there.
ContactState at_step_start(const ContactGeometry& geometry, const ContactFixture& f) {
  ContactState state = tsm::test::reference_state(geometry, f);
  tsm::contact::list_near_candidates(geometry, geometry.contact(0), f.D, tsm::contact::displacement_stamp(f.D),
                                     tsm::contact::CandidateChords(geometry, f.D), state.reference);
  return state;
}

TEST(BroadPhase, ListsTheElementsWithinTheGapABulgeAndEightElementsOfTheNode) {
  // 40 elements of 2.5 cm, a node 10 cm above x = 0.5 with a 5 mm gap: the radius is
  // 0.005 + 0.025 + 8 × 0.025 = 0.23 m, which reaches x = 0.5 ± 0.2071 along the beam: the
  // elements from [0.275, 0.3] to [0.7, 0.725], 18 of them.
  ContactFixture f(0.5, 0.1, {{"gap", 0.005}}, 40);
  const ContactGeometry geometry(f.model);
  const ContactState state = at_step_start(geometry, f);
  std::vector<int> expected;
  for (int ci = 11; ci <= 28; ++ci) expected.push_back(ci);
  EXPECT_EQ(state.reference.near, expected);
  EXPECT_NEAR(state.reference.allowance, 0.2, 1e-15);
}

TEST(BroadPhase, HoldsOnlyAtTheStepsStartAndWhileTheNodeAndTheBeamMoveLessThanTheAllowance) {
  ContactFixture f(0.5, 0.1, {{"gap", 0.005}}, 40);
  const ContactGeometry geometry(f.model);
  const ContactState state = at_step_start(geometry, f);
  const StepStart start = tsm::contact::step_start(f.D, f.rotations);
  const auto listed = [&](const StepStart* from) {
    const BroadPhase broad_phase(geometry, f.D, from);
    return broad_phase.candidates(geometry.contact(0), state.reference) != nullptr;
  };
  EXPECT_TRUE(listed(&start));
  EXPECT_FALSE(listed(nullptr));  // no step start given: every candidate
  f.move_foot(0.0, -0.19);
  EXPECT_TRUE(listed(&start));
  f.move_foot(0.0, -0.21);  // the node has moved more than 0.2 m
  EXPECT_FALSE(listed(&start));
  f.move_foot(0.0, -0.1);
  f.bend_beam(0.11);  // the beam's end rose 0.11 m: 0.1 + 0.11 > 0.2
  EXPECT_FALSE(listed(&start));
  f.bend_beam(0.09);
  EXPECT_TRUE(listed(&start));
  Eigen::VectorXd elsewhere = start.displacements;
  elsewhere[0] = 1e-300;  // another start than the one the list was made at
  const StepStart other = tsm::contact::step_start(elsewhere, f.rotations);
  EXPECT_FALSE(listed(&other));
}

/// Lifts every node of the fixture's beam by `dy` on top of what it has.
void lift_beam(ContactFixture& f, double dy) {
  for (int k = 0; k < f.model.node_count(); ++k)
    if (k != f.foot && f.model.nodes[k].id != 11 && f.model.nodes[k].position.y() == 0.0) f.D[tsm::dofs_per_node * k + 1] += dy;
}

TEST(BroadPhase, DetectionOverTheListedCandidatesFindsWhatDetectionOverEveryOneFinds) {
  // Random steps on a beam of 40 elements (2.5 cm; the allowance is 0.2 m). Half the trials
  // draw the node anywhere near the beam (gap 1 cm), bend the beam and move the node by up to 1.5
  // times the allowance; the other half draw it just within or beyond the radius above the beam
  // (gap 5 cm: the radius is 0.275 m) and close node and beam on each other by up to 1.5 times
  // the allowance, partly by lifting the beam — where a list that forgot the beam's motion or
  // the gap would miss a contact (checked). Detection with the broad phase and without it start the same
  // contact (or none) on the same element from the same side at the same α — and so does a
  // reference as a step's start keeps it: the sides of the listed candidates only, every other
  // side read at the start where the list does not hold (ContactSet::update).
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), fraction(0.0, 1.0);
  int listed = 0, touched = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const bool closing = trial % 2 == 1;
    const double x = closing ? 0.5 + 0.3 * unit(random) : 0.5 + 0.7 * unit(random);
    const double y = closing ? 0.275 + 0.05 * unit(random) : 0.3 * unit(random);
    ContactFixture f(x, y, {{"gap", closing ? 0.05 : 0.01}}, 40);
    const ContactGeometry geometry(f.model);
    const StepStart start = tsm::contact::step_start(f.D, f.rotations);
    ContactState with = at_step_start(geometry, f), without = with, kept;
    tsm::contact::ChordFrames frames_at_start(geometry, f.D);
    tsm::contact::reset_near_sides(geometry, geometry.contact(0), start, tsm::contact::CandidateChords(geometry, f.D),
                                   frames_at_start, kept);
    ASSERT_EQ(kept.reference.side.size(), kept.reference.near.size());
    if (closing) {
      const double closure = 0.3 * fraction(random), lifted = fraction(random);
      f.move_foot(0.0, -(1.0 - lifted) * closure);
      lift_beam(f, lifted * closure);
    } else {
      f.bend_beam(0.1 * unit(random));
      f.move_foot(0.3 * unit(random), 0.3 * unit(random));
    }
    const BroadPhase broad_phase(geometry, f.D, &start);
    const std::vector<int>* near = broad_phase.candidates(geometry.contact(0), with.reference);
    listed += near != nullptr;
    tsm::contact::Occupancy occupied_with(f.model.elements.size()), occupied_without(f.model.elements.size());
    tsm::contact::ChordFrames frames_with(geometry, f.D), frames_without(geometry, f.D);
    const bool a = tsm::contact::detect(geometry, geometry.contact(0), f.D, f.rotations, frames_with, with, occupied_with,
                                        nullptr, near).has_value();
    const bool b = tsm::contact::detect(geometry, geometry.contact(0), f.D, f.rotations, frames_without, without,
                                        occupied_without).has_value();
    const std::vector<int>* kept_near = broad_phase.candidates(geometry.contact(0), kept.reference);
    if (!kept_near) tsm::contact::take_every_side(geometry, geometry.contact(0), start, frames_at_start, kept.reference);
    tsm::contact::Occupancy occupied_kept(f.model.elements.size());
    tsm::contact::ChordFrames frames_kept(geometry, f.D);
    const bool c = tsm::contact::detect(geometry, geometry.contact(0), f.D, f.rotations, frames_kept, kept, occupied_kept,
                                        nullptr, kept_near, &start).has_value();
    ASSERT_EQ(a, b) << "trial " << trial;
    ASSERT_EQ(c, b) << "trial " << trial;
    ASSERT_EQ(with.active, without.active) << "trial " << trial;
    if (!with.active) continue;
    ++touched;
    ASSERT_EQ(with.element, without.element) << "trial " << trial;
    ASSERT_EQ(with.side, without.side) << "trial " << trial;
    ASSERT_EQ(with.alpha, without.alpha) << "trial " << trial;
    ASSERT_EQ(kept.element, without.element) << "trial " << trial;
    ASSERT_EQ(kept.side, without.side) << "trial " << trial;
    ASSERT_EQ(kept.alpha, without.alpha) << "trial " << trial;
  }
  EXPECT_GT(listed, 400) << "steps within the allowance";
  EXPECT_LT(listed, 2600) << "and beyond it";
  EXPECT_GT(touched, 300) << "and many of them touch";
}

}  // namespace
