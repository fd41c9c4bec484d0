#include "tsmframe/util/segment_grid.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

using tsm::util::Segment;
using tsm::util::SegmentGrid;

namespace {

/// The segments whose boxes meet [low, high], by looking at every one.
std::vector<int> scanned(const std::vector<Segment>& segments, const Eigen::Vector2d& low, const Eigen::Vector2d& high) {
  std::vector<int> found;
  for (int s = 0; s < static_cast<int>(segments.size()); ++s) {
    const Eigen::Vector2d a = segments[s].a.cwiseMin(segments[s].b), b = segments[s].a.cwiseMax(segments[s].b);
    if (!((b.array() < low.array()).any() || (a.array() > high.array()).any())) found.push_back(s);
  }
  return found;
}

/// A beam of `n` short elements winding over a plane 100 long, and a few long ones across it.
std::vector<Segment> winding_beam(int n, std::mt19937& random) {
  std::uniform_real_distribution<double> step(-0.3, 0.3), anywhere(-50.0, 50.0);
  std::vector<Segment> segments;
  Eigen::Vector2d x(0.0, 0.0);
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector2d y = x + Eigen::Vector2d(std::abs(step(random)) + 0.05, step(random));
    segments.push_back({x, y});
    x = y;
  }
  for (int k = 0; k < 5; ++k) segments.push_back({{anywhere(random), anywhere(random)}, {anywhere(random), anywhere(random)}});
  return segments;
}

}  // namespace

TEST(SegmentGrid, FindsWhatAScanOfEverySegmentFinds) {
  std::mt19937 random(7);
  const std::vector<Segment> segments = winding_beam(2000, random);
  const SegmentGrid grid(segments);
  ASSERT_TRUE(grid.usable());
  std::uniform_real_distribution<double> where(-20.0, 400.0), size(0.0, 3.0);
  std::vector<int> found;
  for (int q = 0; q < 500; ++q) {
    const Eigen::Vector2d x(where(random), 0.1 * where(random));
    const double r = q % 50 == 0 ? 500.0 : size(random);  // now and then a square holding everything
    grid.near(x, r, found);
    ASSERT_EQ(found, scanned(segments, x.array() - r, x.array() + r)) << "query " << q;
  }
}

TEST(SegmentGrid, ASquareBesideTheSegmentsFindsNothingAndOneTouchingABoxFindsIt) {
  const std::vector<Segment> segments = {{{0.0, 0.0}, {1.0, 0.0}}, {{1.0, 0.0}, {2.0, 1.0}}};
  const SegmentGrid grid(segments);
  std::vector<int> found;
  grid.near({10.0, 10.0}, 1.0, found);
  EXPECT_TRUE(found.empty());
  grid.near({-1.0, 0.0}, 0.5, found);
  EXPECT_TRUE(found.empty());
  grid.in_box({-1.0, -1.0}, {0.0, 0.0}, found);  // meets the first box at one corner
  EXPECT_EQ(found, std::vector<int>{0});
  grid.in_box({2.0, 1.0}, {3.0, 2.0}, found);
  EXPECT_EQ(found, std::vector<int>{1});
}

TEST(SegmentGrid, ASquareAtTheFarEdgeFindsTheSegmentThere) {
  // Three cells of 0.33333333333333337 end at 0.9999999999999999 in doubles, below the second
  // segment's end at 1: a square from x = 1 on still meets it.
  const std::vector<Segment> segments = {{{-8e-17, 0.0}, {-8e-17, 0.001}}, {{0.33433333333333326, 0.0}, {1.0, 0.0}}};
  const SegmentGrid grid(segments);
  std::vector<int> found;
  grid.in_box({1.0, -1.0}, {2.0, 1.0}, found);
  EXPECT_EQ(found, std::vector<int>{1});
  grid.near({1.5, 0.0}, 0.5, found);
  EXPECT_EQ(found, std::vector<int>{1});
}

TEST(SegmentGrid, CoordinatesNotFiniteGiveEverySegmentToEveryQuery) {
  const std::vector<Segment> segments = {{{0.0, 0.0}, {1.0, 0.0}}, {{1.0, 0.0}, {NAN, 1.0}}, {{5.0, 5.0}, {6.0, 5.0}}};
  const SegmentGrid grid(segments);
  EXPECT_FALSE(grid.usable());
  std::vector<int> found;
  grid.near({100.0, 100.0}, 1.0, found);
  EXPECT_EQ(found, (std::vector<int>{0, 1, 2}));
}

TEST(SegmentGrid, HugeAndDegenerateExtentsStayUsableOrFallBackToAScan) {
  std::vector<int> found;
  const std::vector<Segment> point = {{{3.0, 3.0}, {3.0, 3.0}}};
  const SegmentGrid one(point);
  one.near({3.0, 3.0}, 0.0, found);
  EXPECT_EQ(found, std::vector<int>{0});
  const std::vector<Segment> far = {{{-1e308, 0.0}, {0.0, 0.0}}, {{0.0, 0.0}, {1e308, 1e308}}};
  const SegmentGrid wide(far);  // the span overflows: a scan
  wide.near({0.0, 0.0}, 1.0, found);
  EXPECT_EQ(found, (std::vector<int>{0, 1}));
  const SegmentGrid none(std::vector<Segment>{});
  none.near({0.0, 0.0}, 1.0, found);
  EXPECT_TRUE(found.empty());
}
