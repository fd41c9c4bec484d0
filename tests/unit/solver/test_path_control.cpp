// Path control's arc-length root choice (solver/path_control.hpp): of the constraint's two roots,
// the one whose new increment turns least from the step's increment so far.
#include <gtest/gtest.h>

#include "tsmframe/solver/path_control.hpp"

namespace {

using tsm::solver::ArcLengthQuadratic;
using tsm::solver::least_turning_root;

TEST(ArcLengthRoot, TakesTheRootWhoseIncrementTurnsLeast) {
  // (δλ − 1)(δλ + 2) = δλ² + δλ − 2: roots 1 and −2. With nothing prescribed (P² = 0) the new
  // increment's dot product with the old is along_trial + δλ · along_load.
  const ArcLengthQuadratic q{1.0, 1.0, -2.0};
  EXPECT_DOUBLE_EQ(*least_turning_root(q, 0.0, 1.0, 0.0, 0.0), 1.0);    // the load direction points on: +1
  EXPECT_DOUBLE_EQ(*least_turning_root(q, 0.0, -1.0, 0.0, 0.0), -2.0);  // it points back: −2 goes on
}

TEST(ArcLengthRoot, CountsTheLoadFactorsShareWhereDisplacementsArePrescribed) {
  // Roots 1 and −2 again; the displacements' part favours +1 slightly (along_load = 0.1), but
  // the step so far moved λ by Δλ = −1 with P² = 1: the dot product gains Δλ (Δλ + δλ) P²,
  // so it is 0.1 + 0 = 0.1 for +1 and −0.2 + 3 = 2.8 for −2: −2 turns least.
  const ArcLengthQuadratic q{1.0, 1.0, -2.0};
  EXPECT_DOUBLE_EQ(*least_turning_root(q, 0.0, 0.1, -1.0, 1.0), -2.0);
}

TEST(ArcLengthRoot, HasNoneWhereTheQuadraticHasNoRealRoot) {
  EXPECT_FALSE(least_turning_root({1.0, 0.0, 1.0}, 0.0, 1.0, 0.0, 0.0));  // δλ² + 1 = 0
  EXPECT_TRUE(least_turning_root({1.0, 2.0, 1.0}, 0.0, 1.0, 0.0, 0.0));   // a double root, −1
}

TEST(ArcLengthRoot, KeepsItsDigitsWhereTheRootsDifferByOrdersOfMagnitude) {
  // (δλ − 1e-9)(δλ − 1e9): the small root from c / s, not from a difference of large numbers.
  const ArcLengthQuadratic q{1.0, -(1e9 + 1e-9), 1.0};
  EXPECT_NEAR(*least_turning_root(q, 0.0, -1.0, 0.0, 0.0), 1e-9, 1e-24);
  EXPECT_NEAR(*least_turning_root(q, 0.0, 1.0, 0.0, 0.0), 1e9, 1e-6);
}

}  // namespace
