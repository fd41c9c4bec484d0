// The chord's direction angle (element::direction_angle): atan2 by quadrant around atan, which
// every element evaluation uses for the chord rotation. It must agree with std::atan2 to within
// an ulp in every direction, and exactly on the axes (signed zeros included).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "tsmframe/element/chord.hpp"

namespace {

using tsm::element::direction_angle;
using std::numbers::pi;

TEST(DirectionAngle, AgreesWithAtan2InEveryDirectionToAnUlp) {
  double largest = 0.0;
  for (const double size : {1e-300, 1e-9, 0.009, 1.0, 7.3e4, 1e300})
    for (int k = 0; k < 20000; ++k) {
      const double t = -pi + 2.0 * pi * (k + 0.37) / 20000;
      const double x = size * std::cos(t), y = size * std::sin(t);
      const double expected = std::atan2(y, x), got = direction_angle(y, x);
      const double ulp = std::nextafter(std::abs(expected), INFINITY) - std::abs(expected);
      largest = std::max(largest, std::abs(got - expected) / ulp);
      ASSERT_LE(std::abs(got - expected), ulp) << "x " << x << " y " << y;
    }
  std::printf("[figure] direction_angle against std::atan2: largest difference %.2f ulp\n", largest);
  // Near the diagonals the two branches meet: both sides of |x| = |y| agree too.
  for (const double x : {1.0, -1.0})
    for (const double y : {1.0, -1.0})
      for (const double s : {1.0 - 1e-15, 1.0, 1.0 + 1e-15}) EXPECT_NEAR(direction_angle(y * s, x), std::atan2(y * s, x), 4e-16);
}

TEST(DirectionAngle, IsExactOnTheAxes) {
  EXPECT_EQ(direction_angle(0.0, 2.0), 0.0);
  EXPECT_EQ(direction_angle(2.0, 0.0), pi / 2);
  EXPECT_EQ(direction_angle(-2.0, 0.0), -pi / 2);
  EXPECT_EQ(direction_angle(0.0, -2.0), pi);
  EXPECT_EQ(direction_angle(-0.0, -2.0), -pi);  // as atan2: the sign of a zero y picks ±π
  EXPECT_TRUE(std::signbit(direction_angle(-0.0, 2.0)));
  EXPECT_TRUE(std::isnan(direction_angle(NAN, 1.0)));
}

TEST(DirectionAngle, AnUndisplacedChordHasNotTurnedAtAll) {
  // φ0 (initial_chord) and φ (current_chord) come from the same function: at D = 0 the chord
  // rotation is exactly 0 for every direction, so an unloaded structure has exactly zero internal
  // forces (φ0 by std::atan2 and φ by direction_angle differed in the last bit: round-off moments
  // in every element of an arch, and its unloaded steps ended on the round-off criterion).
  const tsm::element::Vector6 zero = tsm::element::Vector6::Zero();
  int turned = 0;
  for (int k = 0; k < 3600; ++k) {
    const double t = 2.0 * pi * (k + 0.123) / 3600;
    const tsm::element::Vector2 start(5.0 * std::cos(t), 5.0 * std::sin(t));
    const tsm::element::Vector2 end(5.0 * std::cos(t + 0.05), 5.0 * std::sin(t + 0.05));
    const tsm::element::InitialChord chord = tsm::element::initial_chord(start, end);
    turned += tsm::element::current_chord(chord, zero, 0.0).rotation != 0.0;
  }
  EXPECT_EQ(turned, 0);
}

}  // namespace
