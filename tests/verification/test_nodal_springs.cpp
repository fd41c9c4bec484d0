// Springs to the ground at nodes ("springs"; issue 29): kx, ky, kr, or k along any direction.
// Against hand calculations (small loads): a cantilever's tip on a spring (parallel stiffness),
// a bar ending in an axial spring (series), a column on a rotational base spring, a skewed
// spring at a tip (the 2×2 tip stiffness plus k d dᵀ); a beam held by springs alone carries its
// load into them; the tangent against finite differences; mechanisms and bad input named.
// Also here: the tangent of an earlier stage's follower loads held dead (stages.hpp).
#include <gtest/gtest.h>

#include <cmath>

#include "support/dense.hpp"
#include "support/models.hpp"
#include "support/unbalanced_jacobian.hpp"
#include "tsmframe/model/stage.hpp"

namespace test_nodal_springs {
namespace {

using namespace tsm::test;

constexpr double E = 2e11, A = 1e-2, I = 1e-4, L = 4.0, EI = E * I, EA = E * A;

/// A steel cantilever along x (node 1 clamped, tip node 2), `divisions` EB elements, a small
/// tip load (P, Q) in one step.
json cantilever(double P, double Q, int divisions = 8) {
  return {{"materials", {{"steel", {{"E", E}}}}},
          {"sections", {{"s", {{"A", A}, {"I", I}}}}},
          {"nodes", json::array({{{"id", 1}, {"x", 0.0}, {"y", 0.0}}, {{"id", 2}, {"x", L}, {"y", 0.0}}})},
          {"members", json::array({{{"from", 1}, {"to", 2}, {"divisions", divisions}, {"material", "steel"}, {"section", "s"}}})},
          {"supports", json::array({{{"node", 1}, {"type", "fixed"}}})},
          {"loads", json::array({{{"node", 2}, {"fx", P}, {"fy", Q}}})},
          {"analysis", {{"tolerance", 1e-12}}}};
}

TEST(NodalSprings, ACantileverTipOnASpringCarriesTheLoadInParallel) {
  const double k = 2.0 * 3.0 * EI / (L * L * L), Q = -1e3;  // the spring twice the tip's own stiffness
  json m = cantilever(0.0, Q);
  m["springs"] = json::array({{{"node", 2}, {"ky", k}}});
  tsm::Model model;
  const tsm::solver::RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  const double v = node_displacement(model, r.steps.back(), 2)[1];
  EXPECT_NEAR(v / (Q / (k + 3.0 * EI / (L * L * L))), 1.0, 1e-6);  // δ = Q / (k + 3EI/L³); geometry ~1e-7
  EXPECT_NEAR(r.steps.back().reactions[1], -Q * 1.0 / 3.0, 1e-6 * std::abs(Q));  // the clamp takes a third
}

TEST(NodalSprings, ABarEndingInAnAxialSpringStretchesInSeries) {
  const double k = EA / L, P = 5e4;  // as stiff as the bar: twice the stretch
  json m = cantilever(P, 0.0, 2);
  m["springs"] = json::array({{{"node", 2}, {"kx", k}}});
  m["supports"].push_back({{"node", 2}, {"fix", {"uy"}}});
  tsm::Model model;
  const tsm::solver::RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  // The spring is beside the bar (both hold node 2): parallel. The series case is a spring holding the bar's end.
  EXPECT_NEAR(node_displacement(model, r.steps.back(), 2)[0] / (P / (EA / L + k)), 1.0, 1e-9);
  // Series: the bar's far end held by the spring alone (node 1 on a kx spring, its uy and rz fixed).
  json series = cantilever(P, 0.0, 2);
  series["supports"] = json::array({{{"node", 1}, {"fix", {"uy", "rz"}}}, {{"node", 2}, {"fix", {"uy", "rz"}}}});
  series["springs"] = json::array({{{"node", 1}, {"kx", k}}});
  const tsm::solver::RunResult s = run(series, model);
  ASSERT_EQ(s.status, tsm::solver::Status::converged) << s.message;
  EXPECT_NEAR(node_displacement(model, s.steps.back(), 2)[0] / (P * (L / EA + 1.0 / k)), 1.0, 1e-9);
}

TEST(NodalSprings, AColumnOnARotationalBaseSpringSwaysByItsTurnToo) {
  // A pinned base with kr: a lateral tip load H turns the base by H L / kr, the tip moves
  // H L³/3EI + H L² / kr.
  const double kr = 10.0 * EI / L, H = 1e2;
  json m = cantilever(0.0, 0.0);
  m["nodes"][1] = {{"id", 2}, {"x", 0.0}, {"y", L}};
  m["supports"] = json::array({{{"node", 1}, {"type", "pinned"}}});
  m["springs"] = json::array({{{"node", 1}, {"kr", kr}}});
  m["loads"] = json::array({{{"node", 2}, {"fx", H}}});
  tsm::Model model;
  const tsm::solver::RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  const double exact = H * L * L * L / (3.0 * EI) + H * L * L / kr;
  EXPECT_NEAR(node_displacement(model, r.steps.back(), 2)[0] / exact, 1.0, 1e-6);
  EXPECT_NEAR(node_displacement(model, r.steps.back(), 1)[2], -H * L / kr, 1e-6 * H * L / kr);
}

TEST(NodalSprings, ASkewedSpringAddsKddTToTheTipsStiffness) {
  // Tip stiffness of a cantilever with its tip rotation free, in (u, v): diag(EA/L, 3EI/L³);
  // a spring k along d = (cos 30°, sin 30°) adds k d dᵀ. Loads small: linear (the bending's
  // shortening, of second order, is 3e-6 of the axial stretch here).
  const double k = 3.0 * EI / (L * L * L), c = std::cos(M_PI / 6), s = std::sin(M_PI / 6);
  json m = cantilever(0.2, -0.1);
  m["springs"] = json::array({{{"node", 2}, {"k", k}, {"direction", {2.0 * c, 2.0 * s}}}});  // any length
  tsm::Model model;
  const tsm::solver::RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  Eigen::Matrix2d K;
  K << EA / L + k * c * c, k * c * s, k * c * s, 3.0 * EI / (L * L * L) + k * s * s;
  const Eigen::Vector2d exact = K.inverse() * Eigen::Vector2d(0.2, -0.1);
  const Eigen::Vector2d tip = node_displacement(model, r.steps.back(), 2).head<2>();
  EXPECT_NEAR(tip.x() / exact.x(), 1.0, 1e-5);
  EXPECT_NEAR(tip.y() / exact.y(), 1.0, 1e-5);
}

TEST(NodalSprings, ABeamHeldBySpringsAloneCarriesItsLoadIntoThem) {
  // No support at all: ky at both ends and kx at one hold a beam (the mechanism check counts
  // springs); the springs carry the load, and their forces balance it.
  const double k = 1e6, Q = -1e4;
  json m = cantilever(0.0, Q);
  m["supports"] = json::array();
  m["loads"] = json::array({{{"node", [] { return json::array({L / 2, 0.0}); }()}, {"fy", Q}}});
  m["springs"] = json::array({{{"node", 1}, {"kx", k}, {"ky", k}}, {{"node", 2}, {"ky", k}}});
  tsm::Model model;
  const tsm::solver::RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  const double v1 = node_displacement(model, r.steps.back(), 1)[1], v2 = node_displacement(model, r.steps.back(), 2)[1];
  EXPECT_NEAR(k * v1, Q / 2.0, 1e-6 * std::abs(Q));  // each end spring takes half
  EXPECT_NEAR(k * v2, Q / 2.0, 1e-6 * std::abs(Q));
  // Without the kx spring the beam may slide along x: a mechanism, named.
  m["springs"][0].erase("kx");
  EXPECT_NE(refusal(m).find("free to move along x"), std::string::npos) << refusal(m);
}

TEST(NodalSprings, TheTangentIsTheJacobian) {
  json m = cantilever(0.0, 0.0, 4);
  m["springs"] = json::array({{{"node", 2}, {"k", 3e5}, {"direction", {1.0, -2.0}}, {"kr", 7e4}},
                              {{"node", 3}, {"kx", 2e5}}});
  const tsm::Model model = tsm::io::read_model(m);
  const tsm::assembly::DofMap dofs(model);
  tsm::assembly::GlobalSystem system(model, dofs);
  system.set_load_factor(0.0);
  Eigen::VectorXd D = Eigen::VectorXd::Zero(model.dof_count());
  for (int k = 0; k < model.dof_count(); ++k)
    if (!model.constrained[k]) D[k] = 0.01 * std::sin(1.7 * k + 0.3);
  std::vector<double> rotations(model.elements.size(), 0.0);
  tsm::assembly::Evaluation e;
  system.evaluate(D, rotations, true, e);
  const Eigen::MatrixXd K = dense_tangent(dofs, system.tangent());
  const Eigen::MatrixXd J = unbalanced_force_jacobian(system, dofs, D, e.chord_rotations, 0.0);
  EXPECT_LE((K - J).cwiseAbs().maxCoeff(), 1e-6 * K.cwiseAbs().maxCoeff());
  // The springs' share is there: without them the tangent differs by about k.
  tsm::Model bare = model;
  bare.springs.clear();
  tsm::assembly::GlobalSystem without(bare, dofs);
  tsm::assembly::Evaluation f;
  std::vector<double> r2(model.elements.size(), 0.0);
  without.evaluate(D, r2, true, f);
  EXPECT_GT((dense_tangent(dofs, without.tangent()) - J).cwiseAbs().maxCoeff(), 1e4);
}

TEST(NodalSprings, ALongBeamOnAnElasticFoundationBendsAsHetenyiSays) {
  // A beam (EI 1, 4 long) on a Winkler foundation k = 10⁴ ("foundation" on the member: springs
  // of k l/2 at each element end along its normal), a point load P at its middle, held along x
  // there only: Hetényi's infinite beam, w = P β/2k · e^{−βx} (cos βx + sin βx), β = (k/4EI)^¼
  // = 7.07 (the ends, 14 decay lengths away, do not matter: e^{−14}). Springs lumped at the
  // nodes of exact cubic elements err by O((βh)⁴): 2.8e-6 of w0 with 200 elements, 1.7e-7 with 400.
  const double k = 1e4, P = -1e-3, beta = std::pow(k / 4.0, 0.25);
  double previous = 0.0;
  for (const int divisions : {50, 100, 200}) {
    json m = beam_model({.L = 4.0, .divisions = divisions});
    m["members"][0]["foundation"] = k;
    m["loads"] = json::array({{{"node", json::array({2.0, 0.0})}, {"fy", P}}});
    m["supports"] = json::array({{{"node", json::array({2.0, 0.0})}, {"fix", {"ux"}}}});
    m["analysis"]["tolerance"] = 1e-12;
    tsm::Model model;
    const tsm::solver::RunResult r = run(m, model);
    ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
    double worst = 0.0;
    const double w0 = P * beta / (2.0 * k);
    for (int n = 0; n < model.node_count(); ++n) {
      const double x = std::abs(model.nodes[n].position.x() - 2.0);
      if (x > 0.6) continue;  // four decay lengths
      const double exact = w0 * std::exp(-beta * x) * (std::cos(beta * x) + std::sin(beta * x));
      worst = std::max(worst, std::abs(r.steps.back().displacements[3 * n + 1] - exact) / std::abs(w0));
    }
    std::printf("[figure] %d elements: w off Hetenyi's by %.2e of w0 at worst (beta h = %.3f)\n", divisions, worst, beta * 4.0 / divisions);
    EXPECT_LT(worst, 0.01 * std::pow(beta * 4.0 / divisions, 4));
    if (previous > 0.0) EXPECT_NEAR(previous / worst, 16.0, 3.0) << "O(h⁴)";
    previous = worst;
  }
}

TEST(NodalSprings, TheReaderRefusesWhatIsNoSpring) {
  json m = cantilever(0.0, -1.0);
  m["springs"] = json::array({{{"node", 2}, {"k", 1.0}}});
  EXPECT_NE(refusal(m).find("springs[0]: give \"k\" with a \"direction\""), std::string::npos) << refusal(m);
  m["springs"][0] = {{"node", 2}, {"ky", 0.0}};
  EXPECT_NE(refusal(m).find("springs[0].ky: must be positive"), std::string::npos) << refusal(m);
  m["springs"][0] = {{"node", 2}, {"k", 1.0}, {"direction", {0.0, 0.0}}};
  EXPECT_NE(refusal(m).find("springs[0].direction: must not be [0, 0]"), std::string::npos) << refusal(m);
  m["springs"][0] = {{"node", 2}};
  EXPECT_NE(refusal(m).find("springs[0]: give kx, ky, kr"), std::string::npos) << refusal(m);
  m["springs"][0] = {{"node", 99}, {"kx", 1.0}};
  EXPECT_NE(refusal(m).find("springs[0].node: unknown node 99"), std::string::npos) << refusal(m);
}

TEST(DeadFollowerLoads, TheirTangentIsTheJacobian) {
  // Stage 2 of a cantilever whose stage 1 left a pressure and a follower tip force held: the
  // tangent's share of them (factor 1, not λ) against central differences.
  json m = cantilever(0.0, 0.0, 5);
  m.erase("loads");
  m["members"][0]["load"] = {{"pressure", 300.0}};
  m["stages"] = json::array({{{"loads", json::array({{{"node", 2}, {"fx", -200.0}, {"fy", 500.0}, {"follower", true}}})}},
                             {{"loads", json::array({{{"node", 2}, {"fy", 100.0}}})}}});
  const tsm::Model staged = tsm::io::read_model(m);
  const tsm::Model model = tsm::stage_model(staged, 1, {{0.9}, Eigen::VectorXd::Zero(staged.dof_count())});
  const tsm::assembly::DofMap dofs(model);
  tsm::assembly::GlobalSystem system(model, dofs);
  const double lambda = 0.4;
  system.set_load_factor(lambda);
  Eigen::VectorXd D = Eigen::VectorXd::Zero(model.dof_count());
  for (int k = 0; k < model.dof_count(); ++k)
    if (!model.constrained[k]) D[k] = (k % 3 == 2 ? 0.8 : 0.3) * std::sin(1.1 * k + 0.2);
  std::vector<double> rotations(model.elements.size(), 0.0);
  tsm::assembly::Evaluation e;
  system.evaluate(D, rotations, true, e);
  ASSERT_GT(e.dead_load.size(), 0);
  const Eigen::MatrixXd K = dense_tangent(dofs, system.tangent(), system.follower_rank_one());
  const Eigen::MatrixXd J = unbalanced_force_jacobian(system, dofs, D, e.chord_rotations, lambda);
  EXPECT_LE((K - J).cwiseAbs().maxCoeff(), 1e-6 * K.cwiseAbs().maxCoeff());
}

}  // namespace

}  // namespace test_nodal_springs
