// Small-load limits with exact answers: the Timoshenko cantilever (exact for any mesh, since
// Eq. 4 is the exact element of a shear-flexible beam under end forces) and the Euler buckling
// load approached by a slightly imperfect pinned column under displacement control.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "support/models.hpp"

namespace {

using namespace tsm::test;
using std::numbers::pi;

class TimoshenkoCantilever : public ::testing::TestWithParam<int> {};

TEST_P(TimoshenkoCantilever, TipDeflectionIsBendingPlusShear) {
  BeamSpec b;
  b.L = 2.0;
  b.E = 5.0;
  b.G = 2.0;
  b.A = 3.0;
  b.I = 1.0;
  b.shear_area = 2.5;  // Ψ = EI/(G A_s) = 1: shear is half the bending deflection
  b.divisions = GetParam();
  b.element = "timoshenko";
  const double P = 1e-7 * b.E * b.I / (b.L * b.L);
  json m = beam_model(b);
  m["supports"] = json::array({{{"node", 1}, {"type", "fixed"}}});
  m["loads"] = json::array({{{"node", 2}, {"fy", P}}});
  const tsm::Model model = tsm::io::read_model(m);
  const auto result = tsm::solver::run_analysis(model);
  ASSERT_EQ(result.status, tsm::solver::Status::converged) << result.message;
  const double exact = P * std::pow(b.L, 3) / (3 * b.E * b.I) + P * b.L / (b.G * b.shear_area);
  EXPECT_NEAR(node_displacement(model, result.steps.back(), 2)[1], exact, 1e-6 * exact);
  expect_global_equilibrium(model, result.steps.back());
}

INSTANTIATE_TEST_SUITE_P(AnyMesh, TimoshenkoCantilever, ::testing::Values(1, 2, 7, 30));

// Steps driven only by prescribed displacements, from an unstressed structure with no loads: the
// step's force level is its drive (a first iterate was measured against a zero scale and ended
// the run as a blow-up).
TEST(PrescribedOnly, ATipMovedSidewaysBendsTheCantileverAsTheLinearFormulaSays) {
  BeamSpec b;  // Euler–Bernoulli, EI = 1, L = 1
  b.divisions = 20;
  const double delta = 1e-4;  // small: the linear answer holds to ~δ²
  json m = beam_model(b);
  m["supports"] = json::array({{{"node", 1}, {"type", "fixed"}}});
  m["prescribed"] = json::array({{{"node", 2}, {"uy", delta}}});
  m["analysis"] = {{"control", {{"type", "load"}, {"steps", 2}}}};
  const tsm::Model model = tsm::io::read_model(m);
  const auto result = tsm::solver::run_analysis(model);
  ASSERT_EQ(result.status, tsm::solver::Status::converged) << result.message;
  const tsm::solver::StepRecord& last = result.steps.back();
  EXPECT_NEAR(node_displacement(model, last, 2)[2], 1.5 * delta, 1e-6 * delta);  // θ = 3δ/(2L)
  // The tip's reaction is the force that holds it there, 3EIδ/L³; the clamp's moment balances it,
  // −3EIδ/L² (clockwise).
  const int tip = model.node_index(2), clamp = model.node_index(1);
  EXPECT_NEAR(last.reactions[3 * tip + 1], 3.0 * delta, 1e-6 * 3.0 * delta);
  EXPECT_NEAR(last.reactions[3 * clamp + 2], -3.0 * delta, 1e-6 * 3.0 * delta);
  expect_global_equilibrium(model, last);
}

TEST(PrescribedOnly, AMovedClampCarriesTheBeamRigidlyWithoutForce) {
  BeamSpec b;
  b.divisions = 20;
  b.element = "timoshenko";
  json m = beam_model(b);
  m["supports"] = json::array({{{"node", 1}, {"type", "fixed"}}});
  m["prescribed"] = json::array({{{"node", 1}, {"ux", 0.3}, {"uy", -0.2}}});
  m["analysis"] = {{"control", {{"type", "load"}, {"steps", 3}}}};
  const tsm::Model model = tsm::io::read_model(m);
  const auto result = tsm::solver::run_analysis(model);
  ASSERT_EQ(result.status, tsm::solver::Status::converged) << result.message;
  const tsm::solver::StepRecord& last = result.steps.back();
  const Eigen::Vector3d tip = node_displacement(model, last, 2);
  EXPECT_NEAR(tip[0], 0.3, 1e-12);
  EXPECT_NEAR(tip[1], -0.2, 1e-12);
  EXPECT_NEAR(tip[2], 0.0, 1e-12);
  EXPECT_LE(last.element_forces.cwiseAbs().maxCoeff(), 1e-9 * b.E * b.A);  // round-off of EA δl
}

class ImperfectColumn : public ::testing::TestWithParam<std::tuple<int, const char*>> {};

TEST_P(ImperfectColumn, LoadApproachesEulerLoad) {
  const auto [n, element] = GetParam();
  const double L = 5.0, E = 2e11, I = 1e-5, A = 1e-2, e0 = 1e-5 * L;
  json m = beam_model({.L = L, .E = E, .G = 8e10, .A = A, .I = I, .shear_area = 1e6 * A, .divisions = 1, .element = element});
  // Half-sine imperfection of amplitude e0, one member per element through explicit nodes.
  m["nodes"] = json::array();
  m["members"] = json::array();
  for (int k = 0; k <= n; ++k)
    m["nodes"].push_back({{"id", k + 1}, {"x", L * k / n}, {"y", e0 * std::sin(pi * k / n)}});
  for (int k = 0; k < n; ++k)
    m["members"].push_back({{"from", k + 1}, {"to", k + 2}, {"element", element}, {"material", "m"}, {"section", "s"}});
  const double Pe = pi * pi * E * I / (L * L);
  m["supports"] = json::array({{{"node", 1}, {"type", "pinned"}}, {{"node", n + 1}, {"type", "roller-x"}}});
  m["loads"] = json::array({{{"node", n + 1}, {"fx", -Pe}}});
  const int mid = n / 2 + 1;
  m["analysis"]["control"] = {{"type", "displacement"}, {"node", mid}, {"dof", "uy"}, {"target", 0.02 * L}, {"steps", 10}};
  m["analysis"]["tolerance"] = 1e-11;  // Σ(reactions + loads) = Σ R_free: the check below needs R small
  const tsm::Model model = tsm::io::read_model(m);
  const auto result = tsm::solver::run_analysis(model);
  ASSERT_EQ(result.status, tsm::solver::Status::converged) << result.message;
  ASSERT_EQ(result.steps.size(), 10u);
  const auto& last = result.steps.back();
  EXPECT_NEAR(node_displacement(model, last, mid)[1], 0.02 * L, 1e-12 * L);
  // v = e0/(1 − P/Pe) before buckling; at v = 0.02 L the load is within 0.5 % of Pe.
  EXPECT_NEAR(last.load_factor, 1.0, 0.005);
  EXPECT_NEAR(result.steps.front().load_factor, 1.0 - e0 / (0.002 * L + e0), 0.005);
  for (const auto& step : result.steps) expect_global_equilibrium(model, step);
}

INSTANTIATE_TEST_SUITE_P(Meshes, ImperfectColumn,
                         ::testing::Values(std::make_tuple(16, "euler-bernoulli"), std::make_tuple(32, "euler-bernoulli"),
                                           std::make_tuple(16, "timoshenko")));

// A member's distributed load ("load": force per unit length), lumped at its elements' ends: a
// small uniform load on a simply supported beam and on a cantilever, against 5wL⁴/384EI and
// wL⁴/8EI. Lumping errs by O(1/n²) at the nodes (40 elements: 6e-4); the supports carry wL.
TEST(DistributedLoad, AUniformLoadBendsABeamAsTheLinearFormulasSay) {
  const double E = 2e11, I = 1e-6, L = 4.0, w = -1e-3;
  for (const bool cantilever : {false, true}) {
    json m = {{"materials", {{"s", {{"E", E}}}}},
              {"sections", {{"x", {{"A", 1e-3}, {"I", I}}}}},
              {"nodes", json::array({{{"id", 1}, {"x", 0.0}, {"y", 0.0}}, {{"id", 2}, {"x", L}, {"y", 0.0}},
                                     {{"id", 3}, {"x", L / 2}, {"y", 0.0}}})},
              {"members", json::array({{{"from", 1}, {"to", 3}, {"divisions", 20}, {"material", "s"}, {"section", "x"},
                                        {"load", {{"fy", w}}}},
                                       {{"from", 3}, {"to", 2}, {"divisions", 20}, {"material", "s"}, {"section", "x"},
                                        {"load", {{"fy", w}}}}})},
              {"analysis", {{"control", {{"type", "load"}, {"steps", 1}}}}}};
    m["supports"] = cantilever ? json::array({{{"node", 1}, {"type", "fixed"}}})
                               : json::array({{{"node", 1}, {"type", "pinned"}}, {{"node", 2}, {"type", "roller-x"}}});
    const tsm::Model model = tsm::io::read_model(m);
    const auto result = tsm::solver::run_analysis(model);
    ASSERT_EQ(result.status, tsm::solver::Status::converged) << result.message;
    const auto& last = result.steps.back();
    const double exact = cantilever ? w * std::pow(L, 4) / (8 * E * I) : 5 * w * std::pow(L, 4) / (384 * E * I);
    const int node = cantilever ? 2 : 3;  // the tip, or mid-span
    EXPECT_NEAR(node_displacement(model, last, node)[1], exact, 1e-3 * std::abs(exact)) << (cantilever ? "cantilever" : "simply supported");
    double carried = 0.0;
    for (int k = 0; k < model.node_count(); ++k) carried += last.reactions[3 * k + 1];
    EXPECT_NEAR(carried, -w * L, 1e-8 * std::abs(w * L));  // to the run's tolerance
    // steps.csv watches each loaded member's middle node, not its 21 loaded nodes — and only the
    // named node once a nodal load names one.
    ASSERT_EQ(model.analysis.monitor.size(), 2u);
    EXPECT_EQ(model.nodes[model.analysis.monitor[0]].position, Eigen::Vector2d(L / 4, 0.0));
    EXPECT_EQ(model.nodes[model.analysis.monitor[1]].position, Eigen::Vector2d(3 * L / 4, 0.0));
    json named = m;
    named["loads"] = json::array({{{"node", 3}, {"fy", w}}});
    const tsm::Model with_load = tsm::io::read_model(named);
    ASSERT_EQ(with_load.analysis.monitor.size(), 1u);
    EXPECT_EQ(with_load.nodes[with_load.analysis.monitor[0]].id, 3);
  }
}

}  // namespace
