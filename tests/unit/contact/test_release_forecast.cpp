// The release look-ahead (solver/release_forecast): the linearised active-set iteration on two
// and three contacts, worked by hand; points coupled on an element against the linear model
// solved again whole for each set.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <cstdio>
#include <random>

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

// ---- points coupled on an element: against the linear model solved whole ----

/// A linear structure K_s (6 dofs) with five contact points: an element with three (entries
/// 0–2, compliance C_0 3×3), one with two (3–4). Point p's gap is g_p = u_pᵀ D + g0_p, an
/// element's forces Y = C⁻¹ g over its points in touch; side −1 (compression = Y).
struct CoupledModel {
  Eigen::MatrixXd Ks, U;
  std::vector<Eigen::MatrixXd> C;
  std::vector<std::vector<int>> points{{0, 1, 2}, {3, 4}};
  Eigen::VectorXd F, g0;

  explicit CoupledModel(unsigned seed) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    const auto matrix = [&](int r, int c) {
      Eigen::MatrixXd m(r, c);
      for (int i = 0; i < r; ++i)
        for (int j = 0; j < c; ++j) m(i, j) = unit(random);
      return m;
    };
    const Eigen::MatrixXd A = matrix(6, 6);
    Ks = A * A.transpose() + 0.5 * Eigen::MatrixXd::Identity(6, 6);
    U = matrix(6, 5);
    for (const std::vector<int>& e : points) {
      const Eigen::MatrixXd B = matrix(static_cast<int>(e.size()), static_cast<int>(e.size()));
      C.push_back(0.2 * (B * B.transpose()) + 0.1 * Eigen::MatrixXd::Identity(e.size(), e.size()));
    }
    F = matrix(6, 1);
    g0 = matrix(5, 1);
  }
  /// The state with the points of `in_touch` in the model: D, and every point's force (0 where
  /// not in touch) and gap beyond its zero-force place (C_RQ Y_Q subtracted; 0 where in touch).
  struct Solution {
    Eigen::VectorXd Y = Eigen::VectorXd::Zero(5), separation = Eigen::VectorXd::Zero(5);
  };
  Solution solve(const std::vector<char>& in_touch) const {
    Eigen::MatrixXd K = Ks;
    Eigen::VectorXd f = F;
    std::vector<std::vector<int>> Q(points.size());
    std::vector<Eigen::MatrixXd> stiffness(points.size());
    for (size_t e = 0; e < points.size(); ++e) {
      for (int p : points[e]) if (in_touch[p]) Q[e].push_back(p);
      if (Q[e].empty()) continue;
      Eigen::MatrixXd CQQ(Q[e].size(), Q[e].size());
      for (size_t a = 0; a < Q[e].size(); ++a)
        for (size_t b = 0; b < Q[e].size(); ++b) CQQ(a, b) = C[e](index(e, Q[e][a]), index(e, Q[e][b]));
      stiffness[e] = CQQ.inverse();
      Eigen::MatrixXd UQ(6, Q[e].size());
      Eigen::VectorXd gQ(Q[e].size());
      for (size_t a = 0; a < Q[e].size(); ++a) UQ.col(a) = U.col(Q[e][a]), gQ[a] = g0[Q[e][a]];
      K += UQ * stiffness[e] * UQ.transpose();  // forces on the structure: −U Y with Y = C⁻¹ g
      f -= UQ * stiffness[e] * gQ;
    }
    const Eigen::VectorXd D = K.llt().solve(f);
    Solution s;
    const Eigen::VectorXd g = U.transpose() * D + g0;
    for (size_t e = 0; e < points.size(); ++e) {
      Eigen::VectorXd gQ(Q[e].size());
      for (size_t a = 0; a < Q[e].size(); ++a) gQ[a] = g[Q[e][a]];
      const Eigen::VectorXd YQ = Q[e].empty() ? Eigen::VectorXd() : Eigen::VectorXd(stiffness[e] * gQ);
      for (size_t a = 0; a < Q[e].size(); ++a) s.Y[Q[e][a]] = YQ[a];
      for (int p : points[e]) {
        if (in_touch[p]) continue;
        double held = 0.0;  // where C Y = g puts it with its own force zero
        for (size_t a = 0; a < Q[e].size(); ++a) held += C[e](index(e, p), index(e, Q[e][a])) * YQ[a];
        s.separation[p] = g[p] - held;
      }
    }
    return s;
  }
  int index(size_t e, int p) const { return static_cast<int>(std::find(points[e].begin(), points[e].end(), p) - points[e].begin()); }
};

TEST(ReleaseForecast, CoupledPointsLetGoAsTheLinearModelSolvedWholeSays) {
  // The active-set iteration run on the model itself (each set solved again whole): from all in
  // touch, the pulling ones let go; then a point let go stays so where it separates, another
  // joins where it would pull. The forecast, from one factorisation and G = Uᵀ K⁻¹ U, ends on
  // the same set. Compression is Y (side −1).
  int compared = 0, coupled_mattered = 0;
  for (unsigned seed = 1; seed <= 200; ++seed) {
    const CoupledModel m(seed);
    const std::vector<char> all(5, 1);
    const CoupledModel::Solution start = m.solve(all);
    std::vector<char> pulling(5);
    for (int p = 0; p < 5; ++p) pulling[p] = start.Y[p] < 0.0;
    if (std::count(pulling.begin(), pulling.end(), 1) == 0) continue;
    std::vector<char> released = pulling, settled;
    for (int round = 0; round < 50 && settled.empty(); ++round) {
      std::vector<char> in_touch(5);
      for (int p = 0; p < 5; ++p) in_touch[p] = !released[p];
      const CoupledModel::Solution s = m.solve(in_touch);
      std::vector<char> next(5);
      for (int p = 0; p < 5; ++p) next[p] = released[p] ? (pulling[p] || s.separation[p] > 0.0) : s.Y[p] < 0.0;
      if (next == released) settled = released;
      released = next;
    }
    if (settled.empty()) continue;
    // The forecast: K with every point in touch, its element's blocks C⁻¹.
    Eigen::MatrixXd K = m.Ks;
    tsm::contact::PointStiffness Z;
    for (size_t e = 0; e < m.points.size(); ++e) {
      Eigen::MatrixXd Ue(6, m.points[e].size());
      for (size_t a = 0; a < m.points[e].size(); ++a) Ue.col(a) = m.U.col(m.points[e][a]);
      K += Ue * m.C[e].inverse() * Ue.transpose();
      Z.add(m.C[e].inverse());
    }
    const Eigen::MatrixXd Gm = m.U.transpose() * K.inverse() * m.U;
    const std::vector<char> forecast = forecast_releases([&](int j) -> Eigen::VectorXd { return Gm.col(j); }, Z, start.Y,
                                                         std::vector<int>(5, -1), std::vector<char>(5, 1));
    EXPECT_EQ(forecast, settled) << "seed " << seed;
    // Each point's own stiffness alone (the diagonal of C⁻¹) would not always say so.
    Eigen::VectorXd diagonal(5);
    for (size_t e = 0; e < m.points.size(); ++e)
      for (size_t a = 0; a < m.points[e].size(); ++a) diagonal[m.points[e][a]] = m.C[e].inverse()(a, a);
    coupled_mattered += forecast_releases(Gm, diagonal, start.Y, std::vector<int>(5, -1), std::vector<char>(5, 1)) != settled;
    ++compared;
  }
  std::printf("coupled points: %d models compared, the diagonal alone wrong in %d\n", compared, coupled_mattered);
  EXPECT_GE(compared, 50);
  EXPECT_GE(coupled_mattered, 5);
}

}  // namespace
