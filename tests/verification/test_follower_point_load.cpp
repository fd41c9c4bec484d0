// Follower point loads ("loads": [{…, "follower": true}]): a nodal force that turns with its
// node. The tangent with its rank-one terms against central differences; a cantilever under a
// tip force that stays normal to the tip against the exact follower elastica, shot here on
//     EI θ'' = −P cos(θ − θ_L),  θ(0) = 0,  θ'(L) = 0,  θ(L) = θ_L
// (the force P (−sin θ_L, cos θ_L) normal to the tip's tangent; RK4 from the tip back to the
// root, bisection on θ_L), in one load step and in ten; the reader's refusals.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>

#include "support/dense.hpp"
#include "support/unbalanced_jacobian.hpp"
#include "support/models.hpp"
#include "support/rk4.hpp"
#include "tsmframe/assembly/dof_map.hpp"
#include "tsmframe/assembly/global_system.hpp"

namespace test_follower_point_load {
namespace {

using namespace tsm::test;

struct Tip {
  double u, v, theta;  // tip displacements / L and rotation, for L = 1
};

/// θ(0) of the follower elastica integrated from the tip (θ = θ_L, θ' = 0) back to the root, with
/// the tip's position relative to the root (∫ cos θ, ∫ sin θ).
std::array<double, 3> from_tip(double p, double theta_tip) {
  const int n = 20000;
  std::array<double, 4> y = {theta_tip, 0.0, 0.0, 0.0};  // θ, θ', x_L − x(s), y_L − y(s); s from L down
  const auto f = [&](const std::array<double, 4>& s) {
    // d/dσ with σ = L − s: θ_σ = −θ', θ'_σ = P cos(θ − θ_L) (EI = 1), the chord back along −t
    return std::array<double, 4>{-s[1], p * std::cos(s[0] - theta_tip), std::cos(s[0]), std::sin(s[0])};
  };
  for (int k = 0; k < n; ++k) y = rk4_step(f, y, 1.0 / n);
  return {y[0], y[2], y[3]};
}

/// The exact tip of a unit inextensible cantilever under a follower tip force p = P L²/EI, normal
/// to the tip (the branch that grows from the unloaded beam: θ_L the first root of θ(0) = 0).
Tip follower_elastica_tip(double p) {
  double lo = 0.0, hi = 0.0;
  while (from_tip(p, hi + 0.01)[0] < 0.0 && hi < 6.0) hi += 0.01;  // θ(0) < 0 until θ_L passes the root
  hi += 0.01;
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (lo + hi);
    (from_tip(p, mid)[0] < 0.0 ? lo : hi) = mid;
  }
  const double theta = 0.5 * (lo + hi);
  const std::array<double, 3> end = from_tip(p, theta);
  return {end[1] - 1.0, end[2], theta};
}

/// A unit cantilever of n Euler–Bernoulli elements (EI 1, EA 1e8: inextensible to the
/// tolerance), clamped at node 1, with a follower force p at its tip (node 2), upward as drawn.
json follower_cantilever(double p, int n, int steps) {
  BeamSpec b;
  b.L = 1.0;
  b.E = 1.0;
  b.G = 1.0;
  b.A = 1e8;
  b.I = 1.0;
  b.shear_area = 1e14;
  b.divisions = n;
  b.element = "euler-bernoulli";
  json m = beam_model(b);
  m["supports"] = json::array({{{"node", 1}, {"type", "fixed"}}});
  m["loads"] = json::array({{{"node", 2}, {"fy", p}, {"follower", true}}});
  m["analysis"]["control"]["steps"] = steps;
  m["analysis"]["tolerance"] = 1e-10;
  return m;
}

TEST(FollowerPointLoad, ShootingReproducesTheLinearLimit) {
  // p → 0: v = PL³/3EI, θ = PL²/2EI; and the force normal to the tip makes u of second order.
  const Tip t = follower_elastica_tip(1e-4);
  EXPECT_NEAR(t.v, 1e-4 / 3.0, 1e-10);
  EXPECT_NEAR(t.theta, 1e-4 / 2.0, 1e-10);
}

TEST(FollowerPointLoad, TheTangentWithItsRankOneTermsIsTheJacobian) {
  json m = follower_cantilever(2.0, 6, 1);
  m["loads"].push_back({{"node", 4}, {"fx", -0.7}, {"fy", 0.3}, {"mz", 0.2}, {"follower", true}});  // an inner node too
  const tsm::Model model = tsm::io::read_model(m);
  ASSERT_EQ(model.follower_forces.size(), 2u);
  const tsm::assembly::DofMap dofs(model);
  tsm::assembly::GlobalSystem system(model, dofs);
  const double lambda = 0.8;
  system.set_load_factor(lambda);
  Eigen::VectorXd D = Eigen::VectorXd::Zero(model.dof_count());
  for (int k = 0; k < model.node_count(); ++k)  // bent and turned by up to a radian: R(θ) matters
    for (int d = 0; d < 3; ++d)
      if (!model.constrained[3 * k + d]) D[3 * k + d] = (d == 2 ? 1.0 : 0.2) * std::sin(1.3 * k + 0.7 * d + 0.4);
  std::vector<double> rotations(model.elements.size(), 0.0);
  tsm::assembly::Evaluation e;
  system.evaluate(D, rotations, true, e);
  EXPECT_EQ(system.follower_rank_one().size(), 2u) << "one rank-one term per follower point load";
  const Eigen::MatrixXd K = dense_tangent(dofs, system.tangent(), system.follower_rank_one());
  const Eigen::MatrixXd J = tsm::test::unbalanced_force_jacobian(system, dofs, D, e.chord_rotations, lambda);
  EXPECT_LE((K - J).cwiseAbs().maxCoeff(), 1e-6 * K.cwiseAbs().maxCoeff());
  // Without the rank-one terms the tangent misses the load's turning: the test can fail.
  EXPECT_GT((dense_tangent(dofs, system.tangent()) - J).cwiseAbs().maxCoeff(), 0.1 * lambda * 0.7);
}

int total_iterations(const tsm::solver::RunResult& r) {
  int n = 0;
  for (const auto& s : r.steps) n += s.iterations;
  return n;
}

class FollowerTip : public ::testing::TestWithParam<std::tuple<double, int>> {};

TEST_P(FollowerTip, MatchesTheFollowerElastica) {
  const auto [p, steps] = GetParam();
  const Tip exact = follower_elastica_tip(p);
  const tsm::Model model = tsm::io::read_model(follower_cantilever(p, 40, steps));
  const auto result = tsm::solver::run_analysis(model);
  ASSERT_EQ(result.status, tsm::solver::Status::converged) << result.message;
  const auto& step = result.steps.back();
  const Eigen::Vector3d tip = node_displacement(model, step, 2);
  // 40 elements: the discrete elastica is within O(h²) of the exact one (the dead-load tip test's 1e-3).
  EXPECT_NEAR(tip[0], exact.u, 1e-3);
  EXPECT_NEAR(tip[1], exact.v, 1e-3);
  EXPECT_NEAR(tip[2], exact.theta, 1e-3);
  std::printf("[figure] follower tip force p = %g in %d step(s): θ_L = %.6f, |Δu| %.1e, |Δv| %.1e, |Δθ| %.1e, %d iterations\n", p,
              steps, exact.theta, std::abs(tip[0] - exact.u), std::abs(tip[1] - exact.v), std::abs(tip[2] - exact.theta),
              total_iterations(result));
  // The support carries the turned force: −p (−sin θ_L, cos θ_L), and its moment about the root.
  const Eigen::Vector2d force(-p * std::sin(tip[2]), p * std::cos(tip[2]));
  EXPECT_NEAR(step.reactions[0], -force.x(), 1e-8 * p);
  EXPECT_NEAR(step.reactions[1], -force.y(), 1e-8 * p);
  const Eigen::Vector2d x_tip = node_position(model, step, 2);
  EXPECT_NEAR(step.reactions[2], -(x_tip.x() * force.y() - x_tip.y() * force.x()), 1e-8 * p);
}

// p = 1, 3, 8: tip rotations of about 0.5, 1.5 and 3 rad (past a right angle: the force then
// points back past the root's vertical), in one step and in ten.
INSTANTIATE_TEST_SUITE_P(Steps, FollowerTip,
                         ::testing::Combine(::testing::Values(1.0, 3.0, 8.0), ::testing::Values(1, 10)));

TEST(FollowerPointLoad, AFollowerForceIsNotADeadOne) {
  // The same p as a dead load ends elsewhere: the test above would fail if "follower" were ignored.
  json dead = follower_cantilever(3.0, 40, 1);
  dead["loads"][0].erase("follower");
  const tsm::Model a = tsm::io::read_model(dead), b = tsm::io::read_model(follower_cantilever(3.0, 40, 1));
  const auto ra = tsm::solver::run_analysis(a), rb = tsm::solver::run_analysis(b);
  ASSERT_EQ(ra.status, tsm::solver::Status::converged);
  ASSERT_EQ(rb.status, tsm::solver::Status::converged);
  EXPECT_GT(std::abs(node_displacement(a, ra.steps.back(), 2)[2] - node_displacement(b, rb.steps.back(), 2)[2]), 0.1);
}

TEST(FollowerPointLoad, TheReaderRefusesWhatCannotTurn) {
  json m = follower_cantilever(1.0, 4, 1);
  m["loads"][0]["follower"] = "yes";
  EXPECT_NE(refusal(m).find("loads[0].follower"), std::string::npos) << refusal(m);
  m["loads"][0] = {{"node", 2}, {"mz", 1.0}, {"follower", true}};
  EXPECT_NE(refusal(m).find("needs a force"), std::string::npos) << refusal(m);
  m = follower_cantilever(1.0, 4, 1);
  m["nodes"].push_back({{"id", 9}, {"x", 0.5}, {"y", 1.0}});  // held by no element
  m["supports"].push_back({{"node", 9}, {"type", "pinned"}});
  m["loads"] = json::array({{{"node", 9}, {"fy", 1.0}, {"follower", true}}});
  EXPECT_NE(refusal(m).find("no rotation to follow"), std::string::npos) << refusal(m);
}

}  // namespace

}  // namespace test_follower_point_load
