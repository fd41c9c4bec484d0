// What a contact may touch and how its law is set up (contact/contact_geometry.hpp).
#include <gtest/gtest.h>

#include <memory>

#include "support/contact_fixture.hpp"

namespace {

using tsm::contact::ContactGeometry;
using tsm::test::ContactFixture;

TEST(ContactGeometry, TheCandidatesAreTheNamedMembersElementsInOrder) {
  ContactFixture f(0.3, 0.1);
  const ContactGeometry geometry(f.model);
  ASSERT_EQ(geometry.contact_count(), 1);
  const auto& contact = geometry.contact(0);
  EXPECT_EQ(contact.node, f.foot);
  EXPECT_EQ(std::vector<int>(contact.candidates.begin(), contact.candidates.end()), (std::vector<int>{0, 1, 2, 3}));
  for (int e = 0; e < 4; ++e) EXPECT_EQ(contact.candidate_index[e], e);
  EXPECT_FALSE(contact.is_candidate(4));  // the post's own elements
  EXPECT_EQ(geometry.candidate_elements(), (std::vector<int>{0, 1, 2, 3}));
}

TEST(ContactGeometry, ContactsThatMayTouchTheSameMembersShareOneCandidateTableThatOutlivesTheGeometryInACopy) {
  ContactFixture f(0.3, 0.1);
  tsm::ContactSpec same = f.model.contacts[0], other = f.model.contacts[0];
  same.node = other.node = f.model.node_index(11);
  other.members = {0, 1};
  f.model.contacts.push_back(same);
  f.model.contacts.push_back(other);
  auto geometry = std::make_unique<ContactGeometry>(f.model);
  EXPECT_EQ(geometry->contact(1).candidates.data(), geometry->contact(0).candidates.data());
  EXPECT_EQ(geometry->contact(1).candidate_index.data(), geometry->contact(0).candidate_index.data());
  EXPECT_NE(geometry->contact(2).candidates.data(), geometry->contact(0).candidates.data());
  EXPECT_EQ(geometry->contact(2).candidates.size(), 6u);  // the beam's four and the post's two
  const ContactGeometry copy = *geometry;
  geometry.reset();
  EXPECT_EQ(std::vector<int>(copy.contact(1).candidates.begin(), copy.contact(1).candidates.end()),
            (std::vector<int>{0, 1, 2, 3}));
  EXPECT_EQ(copy.contact(2).candidate_index[5], 5);
}

TEST(ContactGeometry, ANodeOverAStraightBeamStandsAtItsHeightAndItsPlaceAlongTheElement) {
  ContactFixture f(0.3, 0.1);
  const ContactGeometry geometry(f.model);
  const auto& contact = geometry.contact(0);
  const auto where = geometry.locate(contact, 1, f.D, f.rotations);  // element 1: x from 0.25 to 0.5
  EXPECT_NEAR(where.alpha, 0.2, 1e-15);
  EXPECT_NEAR(where.gap, 0.1, 1e-15);
  // α alone rules an element out: no gap is measured beyond the span asked for.
  EXPECT_TRUE(std::isnan(geometry.locate(contact, 3, f.D, f.rotations, 0.0, 1.0).gap));
  const auto chord = geometry.on_chord(contact, 3, f.D);  // meaningful far beyond the element
  EXPECT_NEAR(chord.alpha, (0.3 - 0.75) / 0.25, 1e-14);
  EXPECT_NEAR(chord.gap, 0.1, 1e-15);
}

TEST(ContactGeometry, TheGapIsMeasuredFromTheElementsDeflectedCentreLine) {
  // The beam's nodes on v = a x², turned to its slope: element 1 runs from (0.25, a/16) to
  // (0.5, a/4) and bends between them under its end rotations against the chord (Eq. 3's free
  // shape, w = l0 α(1 − α)[(1 − α) θ_i − α θ_j]). The gap is the node's distance from that curve
  // along the chord's normal, not from the chord.
  ContactFixture f(0.375, 0.2);
  const double a = 0.1, l0 = 0.25;
  f.bend_beam(a);
  const ContactGeometry geometry(f.model);
  const auto where = geometry.locate(geometry.contact(0), 1, f.D, f.rotations);
  const Eigen::Vector2d xi(0.25, a * 0.0625), xj(0.5, a * 0.25), node(0.375, 0.2);
  const double beta = std::atan2(xj.y() - xi.y(), xj.x() - xi.x());
  const Eigen::Vector2d e(std::cos(beta), std::sin(beta)), n(-std::sin(beta), std::cos(beta));
  const double alpha = (node - xi).dot(e) / (xj - xi).norm();
  const double theta_i = 2.0 * a * 0.25 - beta, theta_j = 2.0 * a * 0.5 - beta;
  const double w = l0 * alpha * (1.0 - alpha) * ((1.0 - alpha) * theta_i - alpha * theta_j);
  EXPECT_NEAR(where.alpha, alpha, 1e-14);
  EXPECT_NEAR(where.gap, (node - xi).dot(n) - w, 1e-14);
  EXPECT_GT(std::abs(w), 1e-4);  // the curve is not the chord here
}

TEST(ContactGeometry, TheStiffnessCapFollowsThePressingElementsAxis) {
  // The post (EA = 1e3, EI = 1, elements 0.25 long) presses along its axis, normal to the beam:
  // the cap is max_stiffness_ratio × EA / l0.
  ContactFixture f(0.3, 0.1, {{"max_stiffness_ratio", 100.0}});
  const ContactGeometry geometry(f.model);
  const auto data = geometry.element_data(geometry.contact(0), 1, 1);
  EXPECT_NEAR(data.min_compliance, 1.0 / (100.0 * 1e3 / 0.25), 1e-18);
  EXPECT_EQ(data.offset, 0.0);
  EXPECT_EQ(data.frame, tsm::ContactFrame::chord);
}

TEST(ContactGeometry, ANamedTheoryOverridesTheTouchedElements) {
  ContactFixture timoshenko(0.3, 0.1, {{"element", "timoshenko"}});
  ContactFixture euler_bernoulli(0.3, 0.1, {{"element", "euler-bernoulli"}});
  const ContactGeometry t(timoshenko.model), e(euler_bernoulli.model);
  // Ψ = EI / (G A_s) = 1 / (0.5 · 1e3) for the fixture's section.
  EXPECT_NEAR(t.element_data(t.contact(0), 1, 1).section.shear_flexibility, 1.0 / (0.5 * 1e3), 1e-15);
  EXPECT_EQ(e.element_data(e.contact(0), 1, 1).section.shear_flexibility, 0.0);
}

TEST(ContactGeometry, AGapOffsetsTheContactOnTheSideItPressesFrom) {
  ContactFixture f(0.3, 0.1, {{"gap", 0.05}});
  const ContactGeometry geometry(f.model);
  EXPECT_EQ(geometry.element_data(geometry.contact(0), 1, 1).offset, 0.05);
  EXPECT_EQ(geometry.element_data(geometry.contact(0), 1, -1).offset, -0.05);
}

}  // namespace
