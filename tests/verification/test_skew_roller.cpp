// A support on an inclined plane (a skew roller, "roller": [dx, dy]; issue 29). The solver takes
// its node's translations along and across the plane as unknowns (model/nodal_frames.hpp).
// Checked: a whole model turned by an angle, its roller-x turned into a skew roller, is the
// original turned, through large rotations, with follower loads, a spring and a pressure at the
// roller, under arc-length control, with a contact pressed then slid onto the roller's element
// in a second stage (exact: the equations do not depend on the frame), Newton's residuals alike
// iterate by iterate (the tangent turned right), and a contact node on a skew roller pressed onto
// a beam; the reactions of a simply supported beam on an inclined roller against statics, loaded
// along its span and on the roller's node; the turned tangent and its rank-one terms against
// central differences; a restart from a kept step; mechanisms and bad input named.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <utility>
#include <sstream>

#include "support/dense.hpp"
#include "support/models.hpp"
#include "tsmframe/io/restart_reader.hpp"
#include "tsmframe/io/results_writer.hpp"
#include "tsmframe/model/nodal_frames.hpp"

namespace test_skew_roller {
namespace {

using namespace tsm::test;

constexpr double E = 2e11, A = 1e-2, I = 1e-4, L = 4.0;

Eigen::Vector2d turned(const Eigen::Vector2d& v, double angle) { return Eigen::Rotation2Dd(angle) * v; }

/// A shallow two-member arch from node 1 (pinned) over node 3 to node 2 on a roller, all turned
/// by `angle`: the roller along the turned x (roller-x when not turned). A crown load large enough
/// to bend the arch flat (the roller travels 0.35 m, a ninth of the span), a follower force at the
/// roller, a pressure on the first member and a spring at the roller.
json turned_arch(double angle) {
  const auto node = [&](int id, double x, double y) {
    const Eigen::Vector2d p = turned({x, y}, angle);
    return json{{"id", id}, {"x", p.x()}, {"y", p.y()}};
  };
  const auto vector = [&](double x, double y) {
    const Eigen::Vector2d p = turned({x, y}, angle);
    return json::array({p.x(), p.y()});
  };
  const Eigen::Vector2d crown = turned({0.0, -2e6}, angle), push = turned({5e4, 2.5e4}, angle);
  json roller = {{"node", 2}};
  if (angle == 0.0) roller["type"] = "roller-x";
  else roller["roller"] = vector(2.0, 0.0);  // any length
  return {{"materials", {{"steel", {{"E", E}}}}},
          {"sections", {{"s", {{"A", A}, {"I", 0.1 * I}}}}},
          {"nodes", json::array({node(1, 0.0, 0.0), node(2, L, 0.0), node(3, L / 2, 0.4)})},
          {"members", json::array({{{"from", 1}, {"to", 3}, {"divisions", 6}, {"material", "steel"}, {"section", "s"}, {"load", {{"pressure", 5e3}}}},
                                   {{"from", 3}, {"to", 2}, {"divisions", 6}, {"material", "steel"}, {"section", "s"}}})},
          {"supports", json::array({{{"node", 1}, {"type", "pinned"}}, roller})},
          {"springs", json::array({{{"node", 2}, {"k", 5e4}, {"direction", vector(1.0, 1.0)}}})},
          {"loads", json::array({{{"node", 3}, {"fx", crown.x()}, {"fy", crown.y()}},
                                 {{"node", 2}, {"fx", push.x()}, {"fy", push.y()}, {"follower", true}}})},
          {"analysis", {{"tolerance", 1e-12}, {"control", {{"type", "load"}, {"steps", 8}}}}}};
}

/// Newton converges alike in both runs, iterate by iterate down to the rounding floor (the
/// turned tangent as good as the plain one; the iterate that lands under the tolerance may differ).
void expect_same_convergence(const tsm::solver::RunResult& a, const tsm::solver::RunResult& b) {
  for (size_t s = 0; s < a.steps.size(); ++s) {
    const std::vector<double>&x = a.steps[s].residual_norms, &y = b.steps[s].residual_norms;
    for (size_t i = 0; i < std::min(x.size(), y.size()) && x[i] > 1e-6; ++i)
      EXPECT_NEAR(y[i] / x[i], 1.0, 1e-3) << "step " << s << ", iteration " << i;
  }
}

/// Steps of two runs, the second of the model turned by `angle`: the largest difference of the
/// displacements turned back, relative to the largest displacement.
double turned_difference(const tsm::solver::RunResult& a, const tsm::solver::RunResult& b, int nodes, double angle) {
  double worst = 0.0, largest = 0.0;
  for (size_t s = 0; s < a.steps.size(); ++s)
    for (int k = 0; k < nodes; ++k) {
      const Eigen::Vector3d u = a.steps[s].displacements.segment<3>(3 * k), w = b.steps[s].displacements.segment<3>(3 * k);
      worst = std::max({worst, (turned(u.head<2>(), angle) - w.head<2>()).norm(), std::abs(u[2] - w[2]) * L});
      largest = std::max(largest, u.head<2>().norm());
    }
  return worst / largest;
}

/// A steel beam of 8 elements from node 1 at the origin to node 2 at `end`, node 100 at `node` a
/// contact node on it (its `gap`), with `supports`.
json beam_and_node_100(const Eigen::Vector2d& end, const Eigen::Vector2d& node, const json& supports, double gap) {
  return {{"materials", {{"steel", {{"E", E}}}}},
          {"sections", {{"s", {{"A", A}, {"I", I}}}}},
          {"nodes", json::array({{{"id", 1}, {"x", 0.0}, {"y", 0.0}}, {{"id", 2}, {"x", end.x()}, {"y", end.y()}},
                                 {{"id", 100}, {"x", node.x()}, {"y", node.y()}}})},
          {"members", json::array({{{"from", 1}, {"to", 2}, {"divisions", 8}, {"material", "steel"}, {"section", "s"}}})},
          {"supports", supports},
          {"contacts", json::array({{{"node", 100}, {"members", "all"}, {"gap", gap}}})},
          {"analysis", {{"tolerance", 1e-12}}}};
}

/// Runs a model as `at(0)` gives it and turned by `angle`: both converge, in as many steps.
std::pair<tsm::solver::RunResult, tsm::solver::RunResult> run_plain_and_turned(const std::function<json(double)>& at,
                                                                               double angle, tsm::Model& plain, tsm::Model& skew) {
  std::pair<tsm::solver::RunResult, tsm::solver::RunResult> runs{run(at(0.0), plain), run(at(angle), skew)};
  EXPECT_EQ(runs.first.status, tsm::solver::Status::converged) << runs.first.message;
  EXPECT_EQ(runs.second.status, tsm::solver::Status::converged) << runs.second.message;
  EXPECT_EQ(runs.first.steps.size(), runs.second.steps.size());
  return runs;
}

TEST(SkewRoller, AModelTurnedWithItsRollerIsTheModelTurned) {
  tsm::Model plain, skew;
  const tsm::solver::RunResult a = run(turned_arch(0.0), plain);
  ASSERT_EQ(a.status, tsm::solver::Status::converged) << a.message;
  const double angle = 0.6;
  const tsm::solver::RunResult b = run(turned_arch(angle), skew);
  ASSERT_EQ(b.status, tsm::solver::Status::converged) << b.message;
  ASSERT_EQ(skew.skew_rollers.size(), 1u);
  ASSERT_EQ(a.steps.size(), b.steps.size());
  expect_same_convergence(a, b);
  const double spread = std::abs(node_displacement(plain, a.steps.back(), 2)[0]);
  EXPECT_GT(spread, 0.08 * L) << "the roller travels far (large rotations)";
  double worst = 0.0, worst_reaction = 0.0, largest_reaction = 0.0;
  for (size_t s = 0; s < a.steps.size(); ++s)
    for (int k = 0; k < plain.node_count(); ++k) {
      const Eigen::Vector3d u = a.steps[s].displacements.segment<3>(3 * k), w = b.steps[s].displacements.segment<3>(3 * k);
      worst = std::max({worst, (turned(u.head<2>(), angle) - w.head<2>()).norm(), std::abs(u[2] - w[2]) * L});
      const Eigen::Vector3d r = a.steps[s].reactions.segment<3>(3 * k), q = b.steps[s].reactions.segment<3>(3 * k);
      worst_reaction = std::max(worst_reaction, (turned(r.head<2>(), angle) - q.head<2>()).norm());
      largest_reaction = std::max(largest_reaction, r.head<2>().norm());
    }
  std::printf("[figure] turned by %.1f rad: displacements off by %.1e of the roller's travel %.3f m, reactions by %.1e\n",
              angle, worst / spread, spread, worst_reaction / largest_reaction);
  EXPECT_LT(worst, 1e-9 * spread);
  EXPECT_LT(worst_reaction, 1e-8 * largest_reaction);
  // The roller's node stays on its plane, exactly (its n is held).
  const Eigen::Vector2d n = turned({0.0, 1.0}, angle);
  for (const auto& step : b.steps) EXPECT_LT(std::abs(n.dot(step.displacements.segment<2>(3 * 1))), 1e-15 * L);
}

TEST(SkewRoller, UnderArcLengthControlTheTurnedModelFollowsTheSamePath) {
  // The arc-length constraint measures translations by their length: the same in any frame. The
  // arc is held at 0.05 (each step's Δs otherwise follows its iteration count, and one iterate
  // more in either model, from rounding — a build at -O1 — parts the two paths step by step).
  tsm::Model plain, skew;
  json a = turned_arch(0.0), b = turned_arch(-1.1);
  for (json* m : {&a, &b})
    (*m)["analysis"]["control"] = {{"type", "arc-length"}, {"initial_increment", 0.05}, {"min_increment", 0.05},
                                   {"max_increment", 0.05}, {"max_steps", 12}};
  const tsm::solver::RunResult ra = run(a, plain), rb = run(b, skew);
  ASSERT_EQ(ra.steps.size(), 12u) << ra.message;
  ASSERT_EQ(rb.steps.size(), 12u) << rb.message;
  for (size_t s = 0; s < ra.steps.size(); ++s) EXPECT_NEAR(ra.steps[s].load_factor, rb.steps[s].load_factor, 1e-9) << s;
  EXPECT_LT(turned_difference(ra, rb, plain.node_count(), -1.1), 1e-9);
}

TEST(SkewRoller, APusherPressingThenSlidingOntoTheRollersElementIsThePlainOneTurned) {
  // Stage 1 presses a rigid pusher 0.2 m into a beam pinned at x = 0 and on a roller at x = L;
  // stage 2 slides it 0.9 m toward the roller, through element ends onto the element that ends
  // at the roller: the contact element's forces, tangent and sliding terms at the roller's node
  // are turned with it.
  const auto beam = [](double angle) {
    const auto xy = [&](double x, double y) { return turned({x, y}, angle); };
    const Eigen::Vector2d end = xy(L, 0.0), pusher = xy(2.9, 0.0), press = xy(0.0, -0.2), slide = xy(0.9, 0.0);
    json roller = {{"node", 2}};
    if (angle == 0.0) roller["type"] = "roller-x";
    else roller["roller"] = {end.x(), end.y()};
    json m = beam_and_node_100(end, pusher, json::array({{{"node", 1}, {"type", "pinned"}}, roller}), 0.0);
    m.update(json{{"stages", json::array({{{"name", "press"}, {"prescribed", json::array({{{"node", 100}, {"ux", press.x()}, {"uy", press.y()}}})},
                                         {"control", {{"type", "load"}, {"steps", 4}}}},
                                        {{"name", "slide"},
                                         {"prescribed", json::array({{{"node", 100}, {"ux", slide.x()}, {"uy", slide.y()}, {"increment", true}}})},
                                         {"control", {{"type", "load"}, {"steps", 18}}}}})}});
    return m;
  };
  tsm::Model plain, skew;
  const auto [a, b] = run_plain_and_turned(beam, 0.8, plain, skew);
  ASSERT_EQ(a.steps.size(), b.steps.size());
  ASSERT_EQ(a.steps.back().contacts.size(), 1u);
  EXPECT_EQ(a.steps.back().contacts[0].element, 7) << "on the element that ends at the roller";
  for (size_t s = 0; s < a.steps.size(); ++s) {
    ASSERT_EQ(a.steps[s].contacts.size(), b.steps[s].contacts.size());
    for (size_t c = 0; c < a.steps[s].contacts.size(); ++c) {
      EXPECT_EQ(a.steps[s].contacts[c].element, b.steps[s].contacts[c].element) << s;
      EXPECT_NEAR(a.steps[s].contacts[c].force, b.steps[s].contacts[c].force, 1e-8 * std::abs(a.steps[s].contacts[c].force)) << s;
    }
  }
  EXPECT_LT(turned_difference(a, b, plain.node_count(), 0.8), 1e-9);
  expect_same_convergence(a, b);
}

TEST(SkewRoller, AContactNodeOnASkewRollerPressedOntoABeamIsThePlainOneTurned) {
  // A node 0.1 above a cantilever (its contact's gap), free to move only across the beam (a
  // roller along y, its rotation held), pressed down onto it in two stages; turned by 0.5 rad
  // the roller is skew and the contact node itself is solved for in its frame.
  const auto model = [](double angle) {
    const auto xy = [&](double x, double y) { return turned({x, y}, angle); };
    const Eigen::Vector2d tip = xy(L, 0.0), node = xy(3.05, 0.1), down = xy(0.0, -2e5), more = xy(0.0, -1e5);
    json roller = {{"node", 100}, {"fix", {"rz"}}};
    if (angle == 0.0) roller["type"] = "roller-y";
    else roller["roller"] = {xy(0.0, 1.0).x(), xy(0.0, 1.0).y()};
    json m = beam_and_node_100(tip, node, json::array({{{"node", 1}, {"type", "fixed"}}, roller}), 0.1);
    m.update(json{{"stages", json::array({{{"name", "press"}, {"loads", json::array({{{"node", 100}, {"fx", down.x()}, {"fy", down.y()}}})},
                                         {"control", {{"type", "load"}, {"steps", 5}}}},
                                        {{"name", "more"}, {"loads", json::array({{{"node", 100}, {"fx", more.x()}, {"fy", more.y()}}})},
                                         {"control", {{"type", "load"}, {"steps", 5}}}}})}});
    return m;
  };
  tsm::Model plain, skew;
  const auto [a, b] = run_plain_and_turned(model, 0.5, plain, skew);
  ASSERT_EQ(a.steps.size(), b.steps.size());
  EXPECT_GT(std::abs(node_displacement(plain, a.steps.back(), 100)[1]), 0.01) << "pressed well into the beam";
  EXPECT_LT(turned_difference(a, b, plain.node_count(), 0.5), 1e-9);
  expect_same_convergence(a, b);
}

TEST(SkewRoller, ARollerAlongXIsRollerX) {
  json m = turned_arch(0.0);
  tsm::Model model;
  const tsm::solver::RunResult a = run(m, model);
  m["supports"][1] = {{"node", 2}, {"roller", {3.0, 0.0}}};
  const tsm::solver::RunResult b = run(m, model);
  EXPECT_TRUE(model.skew_rollers.empty());
  ASSERT_EQ(a.steps.size(), b.steps.size());
  EXPECT_TRUE(a.steps.back().displacements == b.steps.back().displacements);
}

TEST(SkewRoller, ASimplySupportedBeamOnAnInclinedRollerHasTheReactionsOfStatics) {
  // Pinned at x = 0, on a roller inclined at β at x = L, P down at the middle (small: linear).
  // The roller pushes across its plane: R_n = P / (2 cos β); the pin takes the rest,
  // (P/2 tan β, P/2).
  const double P = 1e3;
  for (const double beta : {0.3, -0.9}) {
    json m = beam_model({.L = L, .E = E, .A = A, .I = I, .divisions = 8});
    m["supports"] = json::array({{{"node", 1}, {"type", "pinned"}}, {{"node", 2}, {"roller", {std::cos(beta), std::sin(beta)}}}});
    m["loads"] = json::array({{{"node", json::array({L / 2, 0.0})}, {"fy", -P}}});
    m["analysis"]["tolerance"] = 1e-12;
    tsm::Model model;
    const tsm::solver::RunResult r = run(m, model);
    ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
    const Eigen::VectorXd& R = r.steps.back().reactions;
    const double Rn = P / (2.0 * std::cos(beta));
    EXPECT_NEAR(R[3 * 1 + 0], -Rn * std::sin(beta), 1e-6 * P) << beta;
    EXPECT_NEAR(R[3 * 1 + 1], Rn * std::cos(beta), 1e-6 * P) << beta;
    EXPECT_NEAR(R[0], P / 2 * std::tan(beta), 1e-6 * P) << beta;
    EXPECT_NEAR(R[1], P / 2, 1e-6 * P) << beta;
    // A load (H, V) on the roller's node itself, in 4 steps: the roller takes V across its
    // plane, R_n = −V / cos β, and the pin the rest of H.
    const double H = 300.0, V = -200.0;
    m["loads"] = json::array({{{"node", 2}, {"fx", H}, {"fy", V}}});
    m["analysis"]["control"] = {{"type", "load"}, {"steps", 4}};
    const tsm::solver::RunResult s = run(m, model);
    ASSERT_EQ(s.status, tsm::solver::Status::converged) << s.message;
    const Eigen::VectorXd& Q = s.steps.back().reactions;
    EXPECT_NEAR(Q[3 * 1 + 1], -V, 1e-6 * P) << beta;
    EXPECT_NEAR(Q[3 * 1 + 0], V * std::tan(beta), 1e-6 * P) << beta;
    EXPECT_NEAR(Q[0], -H - V * std::tan(beta), 1e-6 * P) << beta;
  }
}

TEST(SkewRoller, TheTurnedTangentIsTheJacobian) {
  // In the roller's frame: K = ∂(Tᵀ(F − λ P))/∂D_nodal, its follower force's rank-one term turned too.
  const tsm::Model model = tsm::io::read_model(turned_arch(0.6));
  const tsm::assembly::DofMap dofs(model);
  tsm::assembly::GlobalSystem system(model, dofs);
  const tsm::NodalFrames& frames = system.frames();
  const double lambda = 0.7;
  system.set_load_factor(lambda);
  Eigen::VectorXd D = Eigen::VectorXd::Zero(model.dof_count());  // nodal
  for (int k = 0; k < model.dof_count(); ++k)
    if (!model.constrained[k]) D[k] = 0.02 * std::sin(1.7 * k + 0.3);
  const std::vector<double> rotations(model.elements.size(), 0.0);
  const auto residual = [&](const Eigen::VectorXd& nodal, std::vector<double> chords, bool tangent, tsm::assembly::Evaluation& e) {
    Eigen::VectorXd global = nodal;
    frames.to_global(global);
    system.evaluate(global, chords, tangent, e);
    return Eigen::VectorXd(e.internal_force - lambda * e.reference_load);
  };
  tsm::assembly::Evaluation e;
  residual(D, rotations, true, e);
  std::vector<tsm::linalg::RankOne> terms = system.follower_rank_one();
  const Eigen::MatrixXd K = dense_tangent(dofs, system.tangent(), terms);
  const int n = dofs.free_count();
  Eigen::MatrixXd J(n, n);
  const double h = 1e-6;
  for (int c = 0; c < n; ++c) {
    Eigen::VectorXd plus = D, minus = D;
    plus[dofs.dof(c)] += h;
    minus[dofs.dof(c)] -= h;
    tsm::assembly::Evaluation ep, em;
    const Eigen::VectorXd fp = residual(plus, e.chord_rotations, false, ep), fm = residual(minus, e.chord_rotations, false, em);
    for (int r = 0; r < n; ++r) J(r, c) = (fp[dofs.dof(r)] - fm[dofs.dof(r)]) / (2 * h);
  }
  const int t = dofs.equation(3 * 1 + 0);  // the roller's t
  ASSERT_GE(t, 0);
  EXPECT_LT(dofs.equation(3 * 1 + 1), 0) << "its n is held";
  EXPECT_LE((K - J).cwiseAbs().maxCoeff(), 1e-6 * K.cwiseAbs().maxCoeff());
  EXPECT_LE((K.row(t) - J.row(t)).cwiseAbs().maxCoeff(), 1e-6 * K.row(t).cwiseAbs().maxCoeff());
  // Left in global components, the roller's row would be the x row: far off.
  tsm::Model unturned = model;
  unturned.skew_rollers.clear();
  tsm::assembly::GlobalSystem plain(unturned, dofs);
  plain.set_load_factor(lambda);
  tsm::assembly::Evaluation f;
  std::vector<double> chords = rotations;
  plain.evaluate(D, chords, true, f);
  EXPECT_GT((dense_tangent(dofs, plain.tangent(), plain.follower_rank_one()).row(t) - J.row(t)).cwiseAbs().maxCoeff(),
            1e-3 * K.row(t).cwiseAbs().maxCoeff());
}

TEST(SkewRoller, ARestartEndsWhereTheWholeRunDoes) {
  // The kept step's displacements are global; the restart turns the roller's back into its frame
  // (a rounding's worth off the state the whole run held: equal to 1e-12, not bit for bit).
  tsm::Model model;
  const tsm::solver::RunResult whole = run(turned_arch(0.6), model);
  ASSERT_EQ(whole.status, tsm::solver::Status::converged) << whole.message;
  std::ostringstream out;
  tsm::io::write_results_json(out, model, whole);
  const tsm::solver::RestartPoint point = tsm::io::read_restart(json::parse(out.str()), 4, model);
  const tsm::solver::RunResult restarted = tsm::solver::run_analysis(model, {}, nullptr, &point);
  ASSERT_EQ(restarted.status, tsm::solver::Status::converged) << restarted.message;
  const Eigen::VectorXd &a = restarted.steps.back().displacements, &b = whole.steps.back().displacements;
  EXPECT_LT((a - b).lpNorm<Eigen::Infinity>(), 1e-12 * b.lpNorm<Eigen::Infinity>());
}

TEST(SkewRoller, MechanismsAndBadInputAreNamed) {
  // A bar on two rollers both along it slides along itself: a mechanism.
  json m = beam_model({.L = 5.0, .divisions = 4});
  m["nodes"][1] = {{"id", 2}, {"x", 3.0}, {"y", 4.0}};
  m["supports"] = json::array({{{"node", 1}, {"roller", {3.0, 4.0}}}, {{"node", 2}, {"roller", {3.0, 4.0}}}});
  m["loads"] = json::array({{{"node", 2}, {"fx", 1.0}}});
  EXPECT_NE(refusal(m).find("mechanism"), std::string::npos) << refusal(m);
  // Held across at one end, along at the other: it turns about the first.
  m["supports"][1] = {{"node", 2}, {"roller", {-4.0, 3.0}}};
  EXPECT_NE(refusal(m).find("free to rotate"), std::string::npos) << refusal(m);
  m["supports"][0] = {{"node", 1}, {"type", "pinned"}};  // pinned, and held across at the other end: stable
  m["supports"][1] = {{"node", 2}, {"roller", {3.0, 4.0}}};
  EXPECT_EQ(refusal(m), "");
  m["supports"][1] = {{"node", 2}, {"roller", {0.0, 0.0}}};
  EXPECT_NE(refusal(m).find("supports[1].roller: the direction the node rolls along must not be [0, 0]"), std::string::npos) << refusal(m);
  m["supports"][1] = {{"node", 2}, {"roller", {1.0, 1.0}}, {"fix", {"ux"}}};
  EXPECT_NE(refusal(m).find("supports[1].roller: a roller holds the translation across its direction only"), std::string::npos)
      << refusal(m);
  m["supports"][1] = {{"node", 2}, {"roller", {1.0, 1.0}}, {"fix", {"rz"}}};  // a guided support: fine
  EXPECT_EQ(refusal(m), "");
  m["supports"][1] = {{"node", 2}, {"roller", {1.0, 1.0}}};
  m["supports"].push_back({{"node", 2}, {"fix", {"ux"}}});
  EXPECT_NE(refusal(m).find("supports[1].roller: node 2 has its translations held by another support too"), std::string::npos)
      << refusal(m);
  m["supports"].erase(2);
  m["prescribed"] = json::array({{{"node", 2}, {"uy", 0.1}}});
  EXPECT_NE(refusal(m).find("supports[1].roller: node 2 has a prescribed displacement"), std::string::npos) << refusal(m);
  m.erase("prescribed");
  m["analysis"]["control"] = {{"type", "displacement"}, {"node", 2}, {"dof", "ux"}, {"target", 0.1}};
  EXPECT_NE(refusal(m).find("supports[1].roller: node 2 has its translation controlled"), std::string::npos) << refusal(m);
}

}  // namespace

}  // namespace test_skew_roller
