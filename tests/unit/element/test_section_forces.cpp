// The section forces along an element (element/section_forces) against a beam's statics worked
// by hand: end moments alone, a point force between the ends, points given out of order, a push's
// share along the chord; and V
// the slope of M between every two stations.
#include "tsmframe/element/section_forces.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace {

using tsm::element::PointForce;
using tsm::element::section_forces;
using tsm::element::SectionStation;

/// V equals (M(b) − M(a)) / (b − a) on every stretch between stations.
void expect_shear_is_the_moments_slope(const std::vector<SectionStation>& s) {
  for (size_t k = 0; k + 1 < s.size(); ++k) {
    if (s[k + 1].x == s[k].x) continue;  // a point: the jump
    EXPECT_NEAR(s[k].V, (s[k + 1].M - s[k].M) / (s[k + 1].x - s[k].x), 1e-12 * (1.0 + std::abs(s[k].V))) << "stretch " << k;
    EXPECT_EQ(s[k].V, s[k + 1].V) << "stretch " << k;
  }
}

TEST(SectionForces, EndMomentsAloneMakeALinearMomentAndAConstantShear) {
  // (N, M_i, M_j) = (3, 2, 4) on l = 2: M(0) = −M_i = −2, M(l) = M_j = 4, V = (M_i + M_j)/l = 3.
  const auto s = section_forces(2.0, {3.0, 2.0, 4.0}, {});
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[0].x, 0.0);
  EXPECT_EQ(s[1].x, 2.0);
  EXPECT_DOUBLE_EQ(s[0].M, -2.0);
  EXPECT_DOUBLE_EQ(s[1].M, 4.0);
  EXPECT_DOUBLE_EQ(s[0].V, 3.0);
  EXPECT_DOUBLE_EQ(s[0].N, 3.0);
  EXPECT_DOUBLE_EQ(s[1].N, 3.0);
  // Equal and opposite end moments on the element (the ring's M_i = −M, M_j = M): uniform M.
  const auto ring = section_forces(2.0, {0.0, -5.0, 5.0}, {});
  EXPECT_DOUBLE_EQ(ring[0].M, 5.0);
  EXPECT_DOUBLE_EQ(ring[1].M, 5.0);
  EXPECT_DOUBLE_EQ(ring[0].V, 0.0);
}

TEST(SectionForces, APointForceMakesTheShearJumpByItAndTheMomentPeakUnderIt) {
  // A simply supported beam (l = 4) with P = 10 pushing down (Y = −10 along n = +y) at a = 1:
  // M = P a b / l = 7.5 under it (sagging, positive), V = P b / l = 7.5 before it, −P a / l = −2.5
  // after it: a jump of −10 = Y.
  const std::vector<PointForce> points = {{0.25, -10.0}};
  const auto s = section_forces(4.0, {0.0, 0.0, 0.0}, points);
  ASSERT_EQ(s.size(), 4u);
  EXPECT_DOUBLE_EQ(s[1].x, 1.0);
  EXPECT_DOUBLE_EQ(s[2].x, 1.0);
  EXPECT_DOUBLE_EQ(s[0].M, 0.0);
  EXPECT_DOUBLE_EQ(s[1].M, 7.5);
  EXPECT_DOUBLE_EQ(s[2].M, 7.5);
  EXPECT_NEAR(s[3].M, 0.0, 1e-15);
  EXPECT_DOUBLE_EQ(s[0].V, 7.5);
  EXPECT_DOUBLE_EQ(s[2].V, -2.5);
  expect_shear_is_the_moments_slope(s);
}

TEST(SectionForces, PointsGivenOutOfOrderAreStationedAlongTheElement) {
  // Two points with end moments: superposition of the cases above, stations in order of x.
  const std::vector<PointForce> points = {{0.75, 4.0}, {0.5, -2.0}};
  const auto s = section_forces(2.0, {1.0, -1.0, 3.0}, points);
  ASSERT_EQ(s.size(), 6u);
  for (size_t k = 0; k + 1 < s.size(); ++k) EXPECT_LE(s[k].x, s[k + 1].x);
  EXPECT_DOUBLE_EQ(s[0].M, 1.0);   // −M_i
  EXPECT_DOUBLE_EQ(s[5].M, 3.0);   // M_j
  EXPECT_DOUBLE_EQ(s[2].V - s[1].V, -2.0);
  EXPECT_DOUBLE_EQ(s[4].V - s[3].V, 4.0);
  // Under the first point (x = 1, ξ = 0.5): the end moments' 1·0.5 + 3·0.5 = 2, and the points'
  // −Y l ξ(1 − α) terms, 2·2·0.5·0.5 = 1 and −4·2·0.5·0.25 = −1: M = 2.
  EXPECT_DOUBLE_EQ(s[1].M, 2.0);
  expect_shear_is_the_moments_slope(s);
}

TEST(SectionForces, APushsShareAlongTheChordMakesNJumpAndItsLeverACouple) {
  // T = 8 along the chord at α = 0.25 of l = 4, acting ρ = 0.5 above it: the ends share it by the
  // lever rule (N8), N = 0.75 T = 6 before the point and −0.25 T = −2 after it; its couple
  // C = −ρT = −4 (counter-clockwise positive) makes M jump by −C: M = C ξ = −1 just before, C (ξ − 1)
  // = 3 just after, V = C / l = −1 throughout.
  const std::vector<PointForce> points = {{0.25, 0.0, 8.0, 0.5}};
  const auto s = section_forces(4.0, {0.0, 0.0, 0.0}, points);
  ASSERT_EQ(s.size(), 4u);
  EXPECT_DOUBLE_EQ(s[0].N, 6.0);
  EXPECT_DOUBLE_EQ(s[2].N, -2.0);
  EXPECT_DOUBLE_EQ(s[1].M, -1.0);
  EXPECT_DOUBLE_EQ(s[2].M, 3.0);
  EXPECT_NEAR(s[3].M, 0.0, 1e-15);
  EXPECT_DOUBLE_EQ(s[0].V, -1.0);
  EXPECT_DOUBLE_EQ(s[3].V, -1.0);
  expect_shear_is_the_moments_slope(s);
}

TEST(SectionForces, BetweenStationsNAndVAreTheStretchsAndMIsInterpolated) {
  // The simply supported beam of the point-force test: at x = 0.5 M = 3.75 (half way up to 7.5),
  // V = 7.5; at the point itself the values just past it (V = −2.5); at x = 2.5 M = 7.5·(1.5/3).
  const std::vector<PointForce> points = {{0.25, -10.0}};
  const auto s = section_forces(4.0, {0.0, 0.0, 0.0}, points);
  EXPECT_DOUBLE_EQ(tsm::element::section_at(s, 0.5).M, 3.75);
  EXPECT_DOUBLE_EQ(tsm::element::section_at(s, 0.5).V, 7.5);
  EXPECT_DOUBLE_EQ(tsm::element::section_at(s, 1.0).V, -2.5);
  EXPECT_DOUBLE_EQ(tsm::element::section_at(s, 1.0).M, 7.5);
  EXPECT_DOUBLE_EQ(tsm::element::section_at(s, 2.5).M, 3.75);
  EXPECT_DOUBLE_EQ(tsm::element::section_at(s, 4.0).M, s.back().M);
}

}  // namespace
