// Coulomb friction (issue 30, docs/friction.md §7) against closed forms:
// (a) a column's tip pressed onto a stiff plane, then dragged along it and back: it sticks while
//     the column's shear stays below μF, slips at the load the elastica gives (computed here by
//     shooting), carries exactly μ times its compression while slipping, through the plane's
//     element ends, and sticks again on reversal until the top has come back twice the
//     threshold's deflection; the same from a restart in the middle of the drag, bit for bit;
// (c) a stiff block pulled along a foundation: its nodes start to slip one by one at the loads a
//     ladder of springs gives (the stick compliance c_T), the last holding what the others leave.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <sstream>
#include <vector>

#include "support/models.hpp"
#include "support/rk4.hpp"
#include "tsmframe/io/restart_reader.hpp"
#include "tsmframe/io/results_writer.hpp"

namespace {

using namespace tsm::test;
using tsm::contact::FrictionStatus;

constexpr double mu = 0.2, F = 0.25;

/// The inextensible column (EI = 1, L = 1) clamped upright at its top, its tip pinned at the
/// origin and loaded by the plane with (−V, F): the top's offset u from the tip. Shooting on the
/// tip's angle φ0 (from the vertical) until the top's tangent is vertical. Along s from the tip:
/// x' = sin φ, y' = cos φ, φ' = M = −x F − y V.
double elastica_offset(double V) {
  const auto top = [&](double phi0) {
    const auto f = [&](const std::array<double, 3>& q) {
      return std::array<double, 3>{std::sin(q[2]), std::cos(q[2]), -q[0] * F - q[1] * V};
    };
    std::array<double, 3> q = {0.0, 0.0, phi0};
    const int n = 4000;
    for (int k = 0; k < n; ++k) q = rk4_step(f, q, 1.0 / n);
    return q;
  };
  double lo = 0.0, hi = 1.0;  // φ(L) rises with φ0
  for (int it = 0; it < 80; ++it) {
    const double mid = 0.5 * (lo + hi);
    (top(mid)[2] < 0.0 ? lo : hi) = mid;
  }
  return top(0.5 * (lo + hi))[0];
}

/// The column (20 elements) standing 1 mm above a plane of 29 elements (EI = EA = 1e8, both
/// ends clamped) with its tip at the middle of one, contact gap 1 mm: pressed by F at its top
/// (its rotation held, its ux prescribed), then the top moved to 0.3 and back to 0.2.
json dragged_column(int drag_steps = 30, int back_steps = 20) {
  return {{"materials", {{"column", {{"E", 1e8}}}, {"plane", {{"E", 1e8}}}}},
          {"sections", {{"column", {{"A", 1.0}, {"I", 1e-8}}}, {"plane", {{"A", 1.0}, {"I", 1.0}}}}},
          {"nodes", json::array({{{"id", 1}, {"x", -0.95}, {"y", 0.0}}, {{"id", 2}, {"x", 1.95}, {"y", 0.0}},
                                 {{"id", 10}, {"x", 0.0}, {"y", 0.001}}, {{"id", 11}, {"x", 0.0}, {"y", 1.001}}})},
          {"members", json::array({{{"from", 1}, {"to", 2}, {"divisions", 29}, {"material", "plane"}, {"section", "plane"}},
                                   {{"from", 10}, {"to", 11}, {"divisions", 20}, {"material", "column"}, {"section", "column"}}})},
          {"supports", json::array({{{"node", 1}, {"type", "fixed"}}, {{"node", 2}, {"type", "fixed"}},
                                    {{"node", 11}, {"fix", {"rz"}}}})},
          {"contacts", json::array({{{"node", 10}, {"members", {0}}, {"friction", mu}, {"gap", 0.001}}})},
          {"stages", json::array({{{"loads", json::array({{{"node", 11}, {"fy", -F}}})},
                                   {"prescribed", json::array({{{"node", 11}, {"ux", 0.0}}})},
                                   {"control", {{"type", "load"}, {"steps", 2}}}},
                                  {{"prescribed", json::array({{{"node", 11}, {"ux", 0.3}}})},
                                   {"control", {{"type", "load"}, {"steps", drag_steps}}}},
                                  {{"prescribed", json::array({{{"node", 11}, {"ux", 0.2}}})},
                                   {"control", {{"type", "load"}, {"steps", back_steps}}}}})},
          {"analysis", {{"monitor", {10, 11}}}}};
}

double ux(const tsm::Model& model, const tsm::solver::StepRecord& s, int id) {
  return s.displacements[3 * model.node_index(id)];
}

TEST(Friction, AColumnTipSticksThenSlipsAtMuTimesItsLoadAndBackAgain) {
  const double u_s = elastica_offset(mu * F);  // the top's offset when the tip starts to slip
  EXPECT_NEAR(u_s, 0.0185142, 1e-7);           // docs/friction.md §7a
  tsm::Model model;
  const tsm::solver::RunResult result = run(dragged_column(), model);
  ASSERT_EQ(result.status, tsm::solver::Status::converged) << result.message;
  int sticking = 0, slipping = 0, reversed = 0;
  for (const tsm::solver::StepRecord& s : result.steps) {
    ASSERT_EQ(s.contacts.size(), 1u);
    const tsm::solver::ContactPoint& c = s.contacts[0];
    ASSERT_GE(c.element, 0) << "step " << s.step;
    // The compression is F by vertical statics (the plane's tilt is below 1e-9); steps of this
    // stiff model (the plane 1e8 × as stiff as the column) end on round-off, its force balance
    // resolved to ~1e-5 of F.
    const double pressed = s.stage == 0 ? s.load_factor * F : F;
    EXPECT_NEAR(c.force, pressed, 1e-4 * F) << "step " << s.step;
    const double u = ux(model, s, 11), tip = ux(model, s, 10);
    if (s.stage == 1 && u < 0.9 * u_s) {  // sticking: the tip held, the column's shear below μF
      ++sticking;
      EXPECT_EQ(c.friction, FrictionStatus::stick) << "step " << s.step;
      EXPECT_NEAR(tip, 0.0, 1e-8);
      EXPECT_NEAR(c.tangential, 2.69964 * u, 2e-3 * 2.69964 * u);  // s(kL) EI/L³ u, kL = 0.5
    }
    if (s.stage == 1 && u > 1.1 * u_s) {  // slipping: μ times the compression, the shape translated
      ++slipping;
      EXPECT_EQ(c.friction, FrictionStatus::slip) << "step " << s.step;
      EXPECT_NEAR(c.tangential / c.force, mu, 1e-9) << "step " << s.step;
      EXPECT_NEAR(tip, u - u_s, 2e-5) << "step " << s.step;
      EXPECT_NEAR(c.slip, u - u_s, 2e-5) << "step " << s.step;
    }
    if (s.stage == 2 && u > 0.3 - 2 * u_s + 1e-3) EXPECT_EQ(c.friction, FrictionStatus::stick) << "step " << s.step;
    if (s.stage == 2 && u < 0.3 - 2 * u_s - 1e-3) {  // slipping back after 2 u_s
      ++reversed;
      EXPECT_EQ(c.friction, FrictionStatus::slip) << "step " << s.step;
      EXPECT_NEAR(c.tangential / c.force, -mu, 1e-9) << "step " << s.step;
      EXPECT_NEAR(tip, u + u_s, 2e-5) << "step " << s.step;
    }
  }
  EXPECT_GE(sticking, 1);
  EXPECT_GE(slipping, 20);
  EXPECT_GE(reversed, 10);
  const tsm::solver::StepRecord& last = result.steps.back();
  EXPECT_NEAR(ux(model, last, 10), 0.2 + u_s, 2e-5);
  EXPECT_NEAR(last.contacts[0].slip, (0.3 - u_s) + (0.3 - 2 * u_s - 0.2), 4e-5);  // 0.3444574
  EXPECT_GT(last.contacts[0].element, result.steps[2].contacts[0].element);       // through element ends
}

TEST(Friction, ARestartInTheMiddleOfTheDragGoesOnBitForBit) {
  tsm::Model model;
  const json m = dragged_column(12, 6);
  const tsm::solver::RunResult whole = run(m, model);
  ASSERT_EQ(whole.status, tsm::solver::Status::converged) << whole.message;
  std::ostringstream written;
  tsm::io::write_results_json(written, model, whole);
  const int from = 9;  // slipping in the drag
  ASSERT_EQ(whole.steps[from - 1].contacts[0].friction, FrictionStatus::slip);
  const tsm::solver::RestartPoint point = tsm::io::read_restart(json::parse(written.str()), from, model);
  const tsm::solver::RunResult restarted = tsm::solver::run_analysis(model, {}, nullptr, &point);
  ASSERT_EQ(restarted.status, tsm::solver::Status::converged) << restarted.message;
  ASSERT_EQ(restarted.steps.size(), whole.steps.size() - from);
  for (size_t k = 0; k < restarted.steps.size(); ++k) {
    const tsm::solver::StepRecord &a = restarted.steps[k], &b = whole.steps[from + k];
    EXPECT_TRUE(a.displacements == b.displacements) << "step " << b.step;
    EXPECT_EQ(a.contacts[0].tangential, b.contacts[0].tangential) << "step " << b.step;
    EXPECT_EQ(a.contacts[0].slip, b.contacts[0].slip) << "step " << b.step;
    EXPECT_EQ(a.contacts[0].friction, b.contacts[0].friction) << "step " << b.step;
  }
}

/// (c) A straight block of 5 nodes (4 elements of h = 0.1, EA_b = 1e4) resting with a gap of 1 cm
/// on a foundation of 10 pinned elements (l0 = 0.1, EA = 1e5), each node at the middle of one and
/// pressed by P = 1 (μ = 0.3), then pulled at its right end by H. Each sticking node is a spring
/// k_n = 1/c_T = EA/(¼ l0) along the foundation, joined to the next by k_s = EA_b/h: the force
/// entering at the first sticking node j splits by the ladder K_last = k_n,
/// K_i = k_n + k_s K_i+1/(k_s + K_i+1); node j starts to slip at H_j = μ P j + μ P K_j/k_n (F16).
json pulled_block(const std::vector<double>& path) {
  json nodes = json::array(), members = json::array(), supports = json::array(), loads = json::array();
  for (int i = 0; i <= 10; ++i) {
    nodes.push_back({{"id", i + 1}, {"x", 0.1 * i}, {"y", 0.0}});
    supports.push_back({{"node", i + 1}, {"type", "pinned"}});
    if (i < 10) members.push_back({{"from", i + 1}, {"to", i + 2}, {"material", "f"}, {"section", "f"}});
  }
  for (int k = 0; k < 5; ++k) {
    nodes.push_back({{"id", 21 + k}, {"x", 0.25 + 0.1 * k}, {"y", 0.01}});
    loads.push_back({{"node", 21 + k}, {"fy", -1.0}});
    if (k < 4) members.push_back({{"from", 21 + k}, {"to", 22 + k}, {"material", "b"}, {"section", "b"}});
  }
  return {{"materials", {{"f", {{"E", 1e5}}}, {"b", {{"E", 1e4}}}}},
          {"sections", {{"f", {{"A", 1.0}, {"I", 1.0}}}, {"b", {{"A", 1.0}, {"I", 1e-3}}}}},
          {"nodes", nodes},
          {"members", members},
          {"supports", supports},
          {"springs", json::array({{{"node", 21}, {"kx", 1e-3}}})},  // the block held along x before it touches
          {"contacts", json::array({{{"nodes", {21, 22, 23, 24, 25}},
                                     {"members", {0, 1, 2, 3, 4, 5, 6, 7, 8, 9}},
                                     {"friction", 0.3},
                                     {"gap", 0.01}}})},
          {"stages", json::array({{{"loads", loads}, {"control", {{"type", "load"}, {"steps", 1}}}},
                                  {{"loads", json::array({{{"node", 25}, {"fx", 1.0}}})},
                                   {"control", {{"type", "load"}, {"steps", 1}, {"path", path}}}}})}};
}

TEST(Friction, ABlockPulledAlongAFoundationSlipsNodeByNodeAtTheLadderLoads) {
  const double k_n = 1e5 / (0.25 * 0.1), k_s = 1e4 / 0.1, muP = 0.3;
  std::array<double, 5> K{};  // from the pulled end: K[0] the first node's
  K[4] = k_n;
  for (int i = 3; i >= 0; --i) K[i] = k_n + k_s * K[i + 1] / (k_s + K[i + 1]);
  std::vector<double> path;  // just below and just above each node's start of slip
  for (int j = 0; j < 4; ++j) {
    const double H_j = muP * j + muP * K[j] / k_n;
    path.push_back(H_j - 2e-3);
    path.push_back(H_j + 2e-3);
  }
  path.push_back(1.45);  // four slipping, the last holding 0.25
  EXPECT_NEAR(muP * K[0] / k_n, 0.3073213, 1e-7);
  tsm::Model model;
  const tsm::solver::RunResult result = run(pulled_block(path), model);
  ASSERT_EQ(result.status, tsm::solver::Status::converged) << result.message;
  ASSERT_EQ(result.steps.size(), path.size() + 1);
  for (size_t q = 0; q < path.size(); ++q) {
    const tsm::solver::StepRecord& s = result.steps[q + 1];
    const double H = s.load_factor;
    const int slipping = q == path.size() - 1 ? 4 : static_cast<int>((q + 1) / 2);
    double total = 0.0;
    for (int k = 0; k < 5; ++k) {  // contacts in model order: node 21 (far end) … 25 (pulled)
      const tsm::solver::ContactPoint& c = s.contacts[static_cast<size_t>(4 - k)];  // k-th from the pulled end
      total += c.tangential;
      if (k < slipping) {
        EXPECT_EQ(c.friction, FrictionStatus::slip) << "H " << H << " node " << k;
        EXPECT_NEAR(c.tangential, 0.3 * c.force, 1e-9) << "H " << H << " node " << k;
      } else {
        EXPECT_EQ(c.friction, FrictionStatus::stick) << "H " << H << " node " << k;
      }
      if (k == slipping && k < 4)  // the first sticking node takes its ladder share of what is left
        EXPECT_NEAR(c.tangential, (H - muP * slipping) * k_n / K[k], 1e-4 * muP) << "H " << H;
    }
    EXPECT_NEAR(total, H, 1e-7) << "H " << H;
  }
}

TEST(Friction, UnderArcLengthControlTheDragTracesTheSameStates) {
  // The drag of (a) under arc-length control, the top's ux moving with λ: every slipping state
  // is the threshold's shape translated (its slip u − u_s), at μ times the compression (§6: the
  // constraint measures the increment from the last converged state; history is written only at
  // convergence).
  const double u_s = elastica_offset(mu * F);
  json m = dragged_column();
  m["stages"].erase(2);
  m["stages"][1]["control"] = {{"type", "arc-length"}, {"initial_increment", 0.01}, {"max_increment", 0.02},
                               {"max_steps", 40}, {"until", {{"load_factor", 1.0}}}};
  tsm::Model model;
  const tsm::solver::RunResult result = run(m, model);
  int slipping = 0;
  for (const tsm::solver::StepRecord& s : result.steps) {
    if (!s.converged || s.stage != 1) continue;
    const tsm::solver::ContactPoint& c = s.contacts[0];
    const double u = ux(model, s, 11);
    if (u < 1.1 * u_s) continue;
    ++slipping;
    EXPECT_EQ(c.friction, FrictionStatus::slip) << "step " << s.step;
    EXPECT_NEAR(c.tangential / c.force, mu, 1e-9) << "step " << s.step;
    EXPECT_NEAR(c.slip, u - u_s, 2e-5) << "step " << s.step;
  }
  EXPECT_GE(slipping, 20);
}

}  // namespace
