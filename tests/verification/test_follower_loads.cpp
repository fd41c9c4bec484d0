// Follower loads: a member's pressure, normal to its current elements. The tangent's blocks hold
// the symmetric part of the Jacobian (finite differences; all of it on a closed ring, where the
// load is conservative), its rank-one terms the skew rest at a free end. A ring inflated to 1.67
// times its radius against the discrete closed form; the critical external pressure of a ring,
// 3EI/R³ (a load of fixed direction would give 4EI/R³), from the tangent's inertia; a cantilever
// rolled up by pressure; a beam under pressure resting on a knife edge (a contact).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "support/dense.hpp"
#include "support/unbalanced_jacobian.hpp"
#include "support/models.hpp"
#include "tsmframe/assembly/dof_map.hpp"
#include "tsmframe/assembly/global_system.hpp"

namespace {

using namespace tsm::test;
using std::numbers::pi;

/// n elements on a circle of radius R (counter-clockwise, or an arc of `sweep` radians), every
/// element with pressure q (positive: from the inside, the members' left), EA = A, EI = 1. The
/// ring is pinned at node 1 and held in y at the node opposite (rigid motions only); the arc is
/// clamped at node 1, its other end free.
json ring(int n, double q, double A, double sweep = 2 * pi) {
  const bool closed = sweep == 2 * pi;
  json m = {{"materials", {{"m", {{"E", 1.0}, {"G", 0.4}}}}}, {"sections", {{"s", {{"A", A}, {"I", 1.0}}}}}};
  m["nodes"] = json::array();
  m["members"] = json::array();
  const int count = closed ? n : n + 1;
  for (int k = 0; k < count; ++k)
    m["nodes"].push_back({{"id", k + 1}, {"x", std::cos(sweep * k / n)}, {"y", std::sin(sweep * k / n)}});
  for (int k = 0; k < n; ++k)
    m["members"].push_back({{"from", k + 1}, {"to", (k + 1) % count + 1}, {"material", "m"}, {"section", "s"},
                            {"load", {{"pressure", q}}}});
  if (closed) m["supports"] = json::array({{{"node", 1}, {"type", "pinned"}}, {{"node", n / 2 + 1}, {"fix", {"uy"}}}});
  else m["supports"] = json::array({{{"node", 1}, {"type", "fixed"}}});  // a curved cantilever: its free end's load is not conservative
  m["analysis"] = {{"control", {{"type", "load"}, {"steps", 1}}}};
  return m;
}

/// K_ff against central differences of R's negative, F(D) − λ F_ref(D), at a deformed state.
/// `free_end_pressure`: the pressure at an open arch's free end (0: a closed ring).
void check_tangent(const json& m, double free_end_pressure) {
  const bool closed = free_end_pressure == 0.0;
  const tsm::Model model = tsm::io::read_model(m);
  const tsm::assembly::DofMap dofs(model);
  tsm::assembly::GlobalSystem system(model, dofs);
  const double lambda = 0.7;
  system.set_load_factor(lambda);
  Eigen::VectorXd D = Eigen::VectorXd::Zero(model.dof_count());
  for (int k = 0; k < model.node_count(); ++k)  // an uneven bend: every term of the Jacobian matters
    for (int d = 0; d < 3; ++d)
      if (!model.constrained[3 * k + d]) D[3 * k + d] = 0.05 * std::sin(1.7 * k + 2.3 * d + 0.4);
  std::vector<double> rotations(model.elements.size(), 0.0);
  tsm::assembly::Evaluation e;
  system.evaluate(D, rotations, true, e);
  ASSERT_EQ(e.reference_load.size(), model.dof_count()) << "the follower loads at this state";
  const Eigen::MatrixXd K = dense_tangent(dofs, system.tangent(), system.follower_rank_one());
  const Eigen::MatrixXd symmetric = dense_tangent(dofs, system.tangent());
  EXPECT_EQ(system.follower_rank_one().empty(), closed) << "skew terms only where a loaded stretch ends";
  const Eigen::MatrixXd J = tsm::test::unbalanced_force_jacobian(system, dofs, D, e.chord_rotations, lambda);
  // The tangent with its rank-one terms is the Jacobian; its block part the Jacobian's symmetric
  // part. An open arch's load is not conservative: the skew part is its free end's λ (p/2) R.
  EXPECT_LE((K - J).cwiseAbs().maxCoeff(), 1e-6 * K.cwiseAbs().maxCoeff());
  EXPECT_LE((symmetric - 0.5 * (J + J.transpose())).cwiseAbs().maxCoeff(), 1e-6 * K.cwiseAbs().maxCoeff());
  EXPECT_NEAR((J - J.transpose()).cwiseAbs().maxCoeff(), lambda * std::abs(free_end_pressure), 1e-6);
}

TEST(FollowerLoad, OnAClosedRingTheTangentIsTheJacobian) { check_tangent(ring(12, 0.8, 50.0), 0.0); }

TEST(FollowerLoad, OnAnOpenArchTheTangentAndItsSkewTermsAreTheJacobian) {
  check_tangent(ring(10, -0.8, 50.0, 0.8 * pi), -0.8);
}

// Internal pressure q on the regular polygon of n chords: hoop force N = q r cos(π/n) in the
// current radius r and N = EA (r − R)/R, so r = R EA / (EA − q R cos(π/n)) — 1.67 R here. The
// ring stays round and unbent.
TEST(FollowerLoad, ARingInflatedToTwoThirdsMoreThanItsRadius) {
  const int n = 64;
  const double EA = 1e4, q = 4000.0;
  tsm::Model model;
  const auto r = run(ring(n, q, EA), model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  const auto& last = r.steps.back();
  const double exact = EA / (EA - q * std::cos(pi / n));
  ASSERT_GT(exact, 1.6);
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  for (int k = 1; k <= n; ++k) centre += node_position(model, last, k) / n;
  for (int k = 1; k <= n; ++k) {
    EXPECT_NEAR((node_position(model, last, k) - centre).norm(), exact, 1e-10) << "node " << k;
    EXPECT_NEAR(node_displacement(model, last, k)[2], 0.0, 1e-10) << "node " << k;
  }
  for (int k = 0; k < n; ++k) EXPECT_NEAR(last.element_forces[3 * k], q * exact * std::cos(pi / n), 1e-8 * q);
}

// External pressure (negative: from the outside): the ring stays round (a perfect structure)
// and loses stability at 3EI/R³, in its two ovalisation modes; 64 elements find it within 1 %.
TEST(FollowerLoad, ARingUnderExternalPressureBucklesAtThreeEIOverRCubed) {
  const double critical = 3.0;  // EI = R = 1
  tsm::Model model;
  const auto below = run(ring(64, -0.95 * critical, 1e6), model);
  ASSERT_EQ(below.status, tsm::solver::Status::converged) << below.message;
  EXPECT_EQ(below.steps.back().negative_eigenvalues, 0);
  EXPECT_TRUE(below.notes.empty());
  const auto above = run(ring(64, -1.05 * critical, 1e6), model);
  ASSERT_EQ(above.status, tsm::solver::Status::converged) << above.message;
  EXPECT_EQ(above.steps.back().negative_eigenvalues, 2);
  ASSERT_EQ(above.notes.size(), 1u);
  EXPECT_NE(above.notes[0].find("bifurcation point"), std::string::npos) << above.notes[0];
  // In two steps (0.525 and 1.05 of it): bisection on the inertia between them finds it.
  json two = ring(64, -1.05 * critical, 1e6);
  two["analysis"]["control"]["steps"] = 2;
  const auto found = run(two, model);
  ASSERT_EQ(found.status, tsm::solver::Status::converged) << found.message;
  ASSERT_EQ(found.critical_points.size(), 1u);
  EXPECT_NEAR(1.05 * critical * found.critical_points[0].load_factor, critical, 0.01 * critical);
}

// A cantilever under a follower pressure strong enough to turn its tip 3.3 rad, in 5 load steps.
// The load is not conservative (the free end): with the tangent's skew terms Newton converges
// in ≤ 15 iterations a step (without them: 38 steps after cutbacks, 1,729 iterations). The
// clamp holds the pressure's resultant on the deformed beam, −λ p R (x_tip − x_root) (the
// elements' chords add up), and its moment.
TEST(FollowerLoad, ACantileverUnderPressureRollsUpInFewIterations) {
  const double p = 30.0;
  json m = beam_model({.L = 1.0, .E = 1.0, .G = 0.4, .A = 1e4, .I = 1.0, .shear_area = 8e3, .divisions = 40});
  m["members"][0]["load"] = {{"pressure", p}};
  m["supports"] = json::array({{{"node", 1}, {"type", "fixed"}}});
  m["analysis"]["control"] = {{"type", "load"}, {"steps", 5}};
  tsm::Model model;
  const auto r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  ASSERT_EQ(r.steps.size(), 5u);
  for (const auto& s : r.steps) EXPECT_LE(s.iterations, 15) << "step " << s.step;
  const auto& last = r.steps.back();
  EXPECT_GT(std::abs(node_displacement(model, last, 2)[2]), 3.0);
  const Eigen::Vector2d chord = node_position(model, last, 2) - node_position(model, last, 1);
  const Eigen::Vector2d resultant = -p * Eigen::Vector2d(-chord.y(), chord.x());  // −p R (x_tip − x_root)
  const Eigen::Vector3d reaction = last.reactions.segment<3>(3 * model.node_index(1));
  EXPECT_NEAR(reaction[0], -resultant.x(), 1e-8 * p);
  EXPECT_NEAR(reaction[1], -resultant.y(), 1e-8 * p);
  double moment = 0.0;  // of the lumped forces about the root
  for (const tsm::Element& e : model.elements) {
    const Eigen::Vector2d a = node_position(model, last, model.nodes[e.start].id);
    const Eigen::Vector2d b = node_position(model, last, model.nodes[e.end].id);
    const Eigen::Vector2d f = 0.5 * p * Eigen::Vector2d((b - a).y(), -(b - a).x());
    const Eigen::Vector2d root = node_position(model, last, 1);
    for (const Eigen::Vector2d& x : {a, b}) moment += (x - root).x() * f.y() - (x - root).y() * f.x();
  }
  EXPECT_NEAR(reaction[2], -moment, 1e-8 * p);
  EXPECT_EQ(last.negative_eigenvalues, -1) << "a non-conservative load: the inertia tells nothing";
}

// A simply supported beam under a pressure (down on its top, deflecting it ~L/300) resting on a
// knife edge drawn at the contact gap below it, 1 cm off mid-span (off a node): the two-span beam
// of spans a and b, by the three-moment equation M_B = −p (a³ + b³)/(8 (a + b)), carries
// R_A = pa/2 + M_B/a, R_C = pb/2 + M_B/b and the rest on the edge. Within 2e-3 (the lumped load
// errs by O(1/n²), the deflection adds ~1e-4). (A far smaller load, 1e-3 N/m here with 6 mN on
// the edge, fails — a fixed load as well: CHANGELOG.)
TEST(FollowerLoad, ABeamUnderPressureOnAKnifeEdgeCarriesWhatTheThreeMomentEquationSays) {
  const double L = 10.0, p = 1e3, gap = 0.05, a = L / 2 + 0.01, b = L - a;
  json m = {{"materials", {{"s", {{"E", 2e11}}}}},
            {"sections", {{"x", {{"A", 4e-3}, {"I", 2e-5}}}}},
            {"nodes", json::array({{{"id", 1}, {"x", 0.0}, {"y", 0.0}}, {{"id", 2}, {"x", L}, {"y", 0.0}},
                                   {{"id", 7}, {"x", a}, {"y", -gap}}})},
            {"members", json::array({{{"from", 1}, {"to", 2}, {"divisions", 40}, {"material", "s"}, {"section", "x"},
                                      {"load", {{"pressure", p}}}}})},
            {"supports", json::array({{{"node", 1}, {"type", "pinned"}}, {{"node", 2}, {"type", "roller-x"}},
                                      {{"node", 7}, {"type", "fixed"}}})},
            {"contacts", json::array({{{"node", 7}, {"members", "all"}, {"gap", gap}}})},
            {"analysis", {{"control", {{"type", "load"}, {"steps", 2}}}}}};
  tsm::Model model;
  const auto r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  const auto& last = r.steps.back();
  ASSERT_EQ(last.contacts.size(), 1u);
  ASSERT_GE(last.contacts[0].element, 0) << "resting on the edge";
  const double MB = -p * (a * a * a + b * b * b) / (8.0 * (a + b));
  const double RA = p * a / 2.0 + MB / a, RC = p * b / 2.0 + MB / b, RB = p * L - RA - RC;
  EXPECT_NEAR(last.reactions[3 * model.node_index(1) + 1], RA, 2e-3 * RA);
  EXPECT_NEAR(last.reactions[3 * model.node_index(2) + 1], RC, 2e-3 * RC);
  EXPECT_NEAR(last.contacts[0].force, RB, 2e-3 * RB);
}

}  // namespace
