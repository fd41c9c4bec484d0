// The release look-ahead (solver/release_forecast): the linearised active-set iteration on two
// and three contacts, worked by hand.
#include <gtest/gtest.h>

#include "tsmframe/contact/release_forecast.hpp"

namespace {

using tsm::contact::forecast_releases;

// Two contacts, k = 1, G = [[0.5, 0.4], [0.4, 0.5]] (K holds k u uᵀ, so k G_ii < 1), side −1:
// compression = Y. Contact 0 pulls (Y = −1). Let go of alone, its would-be force is
// −1 / (1 − 0.5) = −2 and contact 1's becomes Y_1 + 0.4 · (−2) = Y_1 − 0.8.
const Eigen::MatrixXd G = (Eigen::MatrixXd(2, 2) << 0.5, 0.4, 0.4, 0.5).finished();
const Eigen::VectorXd k = Eigen::VectorXd::Ones(2);
const std::vector<int> side = {-1, -1};

TEST(ReleaseForecast, AContactThatWouldPullOnceTheOtherLetsGoLetsGoWithIt) {
  // Y_1 = 0.3: −0.5 once contact 0 lets go. Both let go: (I − G) Y' = Y gives Y' = (−4.2, −2.8),
  // both pulling: settled.
  const std::vector<char> released = forecast_releases(G, k, Eigen::Vector2d(-1.0, 0.3), side, {1, 1});
  EXPECT_EQ(released, (std::vector<char>{1, 1}));
}

TEST(ReleaseForecast, AContactThatStillPressesStays) {
  // Y_1 = 1: 0.2 once contact 0 lets go.
  EXPECT_EQ(forecast_releases(G, k, Eigen::Vector2d(-1.0, 1.0), side, {1, 1}), (std::vector<char>{1, 0}));
  // Nothing pulls: nothing lets go.
  EXPECT_EQ(forecast_releases(G, k, Eigen::Vector2d(0.5, 1.0), side, {1, 1}), (std::vector<char>{0, 0}));
}

TEST(ReleaseForecast, AnEntryThatMayNotJoinStaysWhateverItsForecast) {
  // As the first case, but contact 1 is a vertex's element.
  EXPECT_EQ(forecast_releases(G, k, Eigen::Vector2d(-1.0, 0.3), side, {1, 0}), (std::vector<char>{1, 0}));
}

TEST(ReleaseForecast, TheSideSetsWhichSignIsAPull) {
  // Side +1: compression = −Y. The first case mirrored.
  EXPECT_EQ(forecast_releases(G, k, Eigen::Vector2d(1.0, -0.3), {1, 1}, {1, 1}), (std::vector<char>{1, 1}));
}

TEST(ReleaseForecast, AChainOfThreeLetsGoStepByStepInOneForecast) {
  // Contact 0 couples to 1 and 1 to 2 only (I − G positive definite, as K ⊇ Σ k u uᵀ makes it):
  // 0 pulls; once it lets go 1 would (0.1 − 0.2 · 2 = −0.3); once both have, 2 would
  // (0.1 + 0.2 · (−0.714) = −0.043); all three let go: Y' = (−2.31, −0.77, −0.11), settled.
  const Eigen::MatrixXd chain = (Eigen::MatrixXd(3, 3) << 0.5, 0.2, 0.0, 0.2, 0.5, 0.2, 0.0, 0.2, 0.5).finished();
  const std::vector<char> released =
      forecast_releases(chain, Eigen::VectorXd::Ones(3), Eigen::Vector3d(-1.0, 0.1, 0.1), {-1, -1, -1}, {1, 1, 1});
  EXPECT_EQ(released, (std::vector<char>{1, 1, 1}));
  // Allowed a set of two at most, it gives up at three: only the pulling one.
  EXPECT_EQ(forecast_releases(chain, Eigen::VectorXd::Ones(3), Eigen::Vector3d(-1.0, 0.1, 0.1), {-1, -1, -1}, {1, 1, 1}, 50, 2),
            (std::vector<char>{1, 0, 0}));
  // With one round only it has not settled: only the pulling one.
  EXPECT_EQ(forecast_releases(chain, Eigen::VectorXd::Ones(3), Eigen::Vector3d(-1.0, 0.1, 0.1), {-1, -1, -1}, {1, 1, 1}, 1),
            (std::vector<char>{1, 0, 0}));
}

}  // namespace
