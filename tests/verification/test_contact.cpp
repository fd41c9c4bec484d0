// Contact verification (issue 3): a cantilever pushed by a rigid point against the linear
// formula 3EIh/a³ (and its Timoshenko counterpart) and against an exact elastica-with-contact
// solution computed here by shooting; a point pushed along the beam across many element ends;
// release on unloading; a node crossing the beam within one step; two contacts at once;
// beam-on-beam; and the assembled tangent with active contacts against finite differences.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <numbers>
#include <cmath>

#include <Eigen/Dense>

#include "support/dense.hpp"
#include "support/models.hpp"
#include "support/rk4.hpp"
#include "tsmframe/assembly/global_system.hpp"
#include "tsmframe/contact/contact_set.hpp"
#include "tsmframe/model/mechanism.hpp"
#include "tsmframe/model/resting_contact.hpp"

namespace {

using namespace tsm::test;
using tsm::solver::RunResult;
using tsm::solver::StepRecord;

/// A cantilever along x (node 1 clamped) and a rigid pusher, node 100 at (x, y0), moved by
/// (push_x, push_y) at λ = 1; the pusher's rotation and, unless pushed along x, its x are fixed.
json pusher_model(const BeamSpec& b, double x, double y0, double push_x, double push_y, int steps) {
  json m = beam_model(b);
  m["nodes"].push_back({{"id", 100}, {"x", x}, {"y", y0}});
  json fix = json::array({"rz"});
  if (push_x == 0.0) fix.push_back("ux");
  m["supports"] = json::array({{{"node", 1}, {"type", "fixed"}}, {{"node", 100}, {"fix", fix}}});
  json prescribed = {{"node", 100}, {"uy", push_y}};
  if (push_x != 0.0) prescribed["ux"] = push_x;
  m["prescribed"] = json::array({prescribed});
  m["contacts"] = json::array({{{"node", 100}, {"members", "all"}}});
  m["analysis"] = {{"control", {{"type", "load"}, {"steps", steps}}}, {"cutback", true}};
  return m;
}

/// Global equilibrium to the accuracy the step reports: a contact next to a beam node is so stiff
/// that its residual may stop at a round-off floor above 1e-9 (criterion "round-off").
void expect_equilibrium(const tsm::Model& model, const StepRecord& step) {
  expect_global_equilibrium(model, step, std::max(1e-9, 10.0 * step.residual_norms.back()));
}

const tsm::solver::ContactPoint& contact_of(const StepRecord& step, size_t k = 0) { return step.contacts.at(k); }

/// Arc length of the contact point from the clamp on a uniform mesh of n elements of length L/n.
double contact_arc_length(const tsm::solver::ContactPoint& c, double L, int n) {
  return (c.element + c.alpha) * L / n;
}

// ---- Exact elastica with a frictionless point contact ----
// Inextensible cantilever (EI = 1, clamped at the origin along x) pushed by a point fixed at
// (a, h): the force is normal to the beam at the contact, P (−sin θc, cos θc); beyond the
// contact the beam is straight. Shooting on (P, θc): integrate EI θ' = M(s) = (a − x) Fy − (h − y) Fx
// from s = 0 until x = a, then y = h and θ = θc must hold.
struct ElasticaContact {
  double force;        // P / EI (for L = 1)
  double arc_length;   // s_c of the contact point
};

std::array<double, 3> integrate_to(double a, double h, double P, double theta_c, double& s_end) {
  const double Fx = -P * std::sin(theta_c), Fy = P * std::cos(theta_c);
  auto f = [&](const std::array<double, 3>& q) {  // q = (x, y, θ)
    return std::array<double, 3>{std::cos(q[2]), std::sin(q[2]), (a - q[0]) * Fy - (h - q[1]) * Fx};
  };
  auto rk4 = [&](const std::array<double, 3>& q, double ds) { return rk4_step(f, q, ds); };
  const double ds = 1e-4;
  std::array<double, 3> q = {0.0, 0.0, 0.0};
  double s = 0.0;
  while (true) {
    const std::array<double, 3> next = rk4(q, ds);
    if (next[0] >= a) {  // the contact lies within this step: bisect its length
      double lo = 0.0, hi = ds;
      for (int it = 0; it < 60; ++it) {
        const double mid = 0.5 * (lo + hi);
        (rk4(q, mid)[0] < a ? lo : hi) = mid;
      }
      s_end = s + 0.5 * (lo + hi);
      return rk4(q, 0.5 * (lo + hi));
    }
    q = next;
    s += ds;
    if (s > 10.0) {
      s_end = s;
      return q;
    }
  }
}

ElasticaContact elastica_with_contact(double a, double h) {
  double P = 3.0 * h / (a * a * a), theta = 1.5 * h / a, s = 0.0;
  for (int it = 0; it < 50; ++it) {
    auto residual = [&](double p, double t) {
      double s_end = 0.0;
      const std::array<double, 3> q = integrate_to(a, h, p, t, s_end);
      return Eigen::Vector2d(q[1] - h, q[2] - t);
    };
    const Eigen::Vector2d r = residual(P, theta);
    if (r.norm() < 1e-12) break;
    Eigen::Matrix2d J;
    const double dp = 1e-7 * P, dt = 1e-7;
    J.col(0) = (residual(P + dp, theta) - r) / dp;
    J.col(1) = (residual(P, theta + dt) - r) / dt;
    const Eigen::Vector2d step = J.colPivHouseholderQr().solve(-r);
    P += step[0];
    theta += step[1];
  }
  integrate_to(a, h, P, theta, s);
  return {P, s};
}

TEST(ElasticaContactReference, TendsToTheLinearFormulaForATinyPush) {
  const ElasticaContact e = elastica_with_contact(0.5, 1e-5);
  EXPECT_NEAR(e.force, 3.0 * 1e-5 / 0.125, 1e-4 * e.force);
  EXPECT_NEAR(e.arc_length, 0.5, 1e-6);
}

// ---- Small push: the linear formula, contact on a beam node and inside an element ----

struct SmallPushCase {
  const char* element;
  double x;  // 0.5: exactly on node 21 (α = 1 | 0, the edge case); 0.5125: mid-element
};

class SmallPush : public ::testing::TestWithParam<SmallPushCase> {};

TEST_P(SmallPush, ForceIsThreeEIhOverACubedPlusShear) {
  const SmallPushCase& p = GetParam();
  BeamSpec b;
  b.divisions = 40;
  b.A = 1e6;
  b.element = p.element;  // G = 0.5, shear_area = 1e3: shear adds a/(G A_s) = 2.4 % of the compliance
  const double h = 1e-6;
  tsm::Model model;
  const RunResult r = run(pusher_model(b, p.x, 0.0, 0.0, h, 1), model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  const double a = p.x;
  const bool timoshenko = std::string(p.element) == "timoshenko";
  const double compliance = a * a * a / (3.0 * b.E * b.I) + (timoshenko ? a / (b.G * b.shear_area) : 0.0);
  const StepRecord& last = r.steps.back();
  ASSERT_GE(contact_of(last).element, 0);
  EXPECT_NEAR(contact_of(last).force, h / compliance, 1e-4 * h / compliance);
  EXPECT_NEAR(contact_arc_length(contact_of(last), 1.0, 40), a, 1e-9);
  expect_equilibrium(model, last);
}

INSTANTIATE_TEST_SUITE_P(Cases, SmallPush,
                         ::testing::Values(SmallPushCase{"euler-bernoulli", 0.5}, SmallPushCase{"timoshenko", 0.5},
                                           SmallPushCase{"euler-bernoulli", 0.5125},
                                           SmallPushCase{"timoshenko", 0.5125}));

/// A beam (10 m, 20 Timoshenko elements, steel) resting on two knife edges drawn at the contact
/// gap (5 cm) below it at x = 1.25 and 8.75 m, held otherwise only along x at mid-span, loaded
/// by `fy` at mid-span.
json beam_on_knife_edges(double fy, int steps) {
  json m = {{"materials", {{"steel", {{"E", 2e11}, {"G", 7.7e10}}}}},
            {"sections", {{"s", {{"A", 0.004}, {"I", 2e-5}, {"shear_area", 0.002}}}}},
            {"nodes", json::array({{{"id", 1}, {"x", 0.0}, {"y", 0.0}}, {{"id", 2}, {"x", 10.0}, {"y", 0.0}},
                                   {{"id", 3}, {"x", 5.0}, {"y", 0.0}}, {{"id", 7}, {"x", 1.25}, {"y", -0.05}},
                                   {{"id", 8}, {"x", 8.75}, {"y", -0.05}}})},
            {"supports", json::array({{{"node", 7}, {"type", "fixed"}}, {{"node", 8}, {"type", "fixed"}},
                                      {{"node", 3}, {"fix", {"ux"}}}})},
            {"loads", json::array({{{"node", 3}, {"fy", fy}}})},
            {"contacts", json::array({{{"node", 7}, {"members", "all"}, {"gap", 0.05}},
                                      {{"node", 8}, {"members", "all"}, {"gap", 0.05}}})},
            {"analysis", {{"control", {{"type", "load"}, {"steps", steps}}}}}};
  const auto member = [](int from, int to) {
    return json{{"from", from}, {"to", to}, {"divisions", 10}, {"element", "timoshenko"}, {"material", "steel"}, {"section", "s"}};
  };
  m["members"] = json::array({member(1, 3), member(3, 2)});
  return m;
}

TEST(ContactResting, ABeamHeldOnlyByTheKnifeEdgesItRestsOnIsSimplySupported) {
  // Before, the model was refused ("free to move along y"): contacts were no supports, and the
  // first solve would have been singular. A contact whose node is drawn at its gap from an
  // element is in contact from the start and counts as a support along the normal. A small
  // load: the linear simply supported beam over the 7.5 m between the edges,
  // δ = P L³/48EI + P L/4GA_s, each edge carrying P/2 (the contact points move ~0.1 mm along the
  // beam as it turns over the edges, at half its depth: ~1e-5 here).
  const double P = 1e3, L = 7.5, EI = 2e11 * 2e-5, GAs = 7.7e10 * 2e-3;
  for (const int steps : {1, 4}) {
    tsm::Model model;
    const RunResult r = run(beam_on_knife_edges(-P, steps), model);
    ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
    const StepRecord& last = r.steps.back();
    for (size_t k = 0; k < 2; ++k) {
      ASSERT_GE(contact_of(last, k).element, 0) << "edge " << k;
      EXPECT_NEAR(contact_of(last, k).force, P / 2.0, 1e-5 * P) << "edge " << k;
    }
    EXPECT_NEAR(node_displacement(model, last, 3)[1], -(P * L * L * L / (48.0 * EI) + P * L / (4.0 * GAs)),
                1e-4 * P * L * L * L / (48.0 * EI));
    expect_equilibrium(model, last);
  }
}

// A simply supported steel beam (10 m) on a knife edge at mid-span under 1 mN/m: 6 mN on the edge,
// deflections of 1e-8 m, where the contact force's rounding is ~1e-6 N. The residual stays at half
// the load: the run says the load is too small to resolve, not only that 50 iterations ran out.
// Ten times the load converges.
TEST(ContactResting, ALoadTooSmallToResolveSaysSo) {
  json m = {{"materials", {{"s", {{"E", 2e11}}}}},
            {"sections", {{"x", {{"A", 4e-3}, {"I", 2e-5}}}}},
            {"nodes", json::array({{{"id", 1}, {"x", 0.0}, {"y", 0.0}}, {{"id", 2}, {"x", 10.0}, {"y", 0.0}},
                                   {{"id", 7}, {"x", 5.01}, {"y", -0.05}}})},
            {"members", json::array({{{"from", 1}, {"to", 2}, {"divisions", 40}, {"material", "s"}, {"section", "x"},
                                      {"load", {{"fy", -1e-3}}}}})},
            {"supports", json::array({{{"node", 1}, {"type", "pinned"}}, {{"node", 2}, {"type", "roller-x"}},
                                      {{"node", 7}, {"type", "fixed"}}})},
            {"contacts", json::array({{{"node", 7}, {"members", "all"}, {"gap", 0.05}}})},
            {"analysis", {{"control", {{"type", "load"}, {"steps", 1}}}, {"cutback", false}}}};
  tsm::Model model;
  const RunResult r = run(m, model);
  ASSERT_NE(r.status, tsm::solver::Status::converged);
  EXPECT_NE(r.message.find("the loads are too small against what rounding leaves in this model's forces to be resolved"),
            std::string::npos)
      << r.message;
  EXPECT_LT(r.steps.back().iterations, 10) << "said at once, not after max_iterations";
  m["members"][0]["load"]["fy"] = -1e-2;
  const RunResult larger = run(m, model);
  EXPECT_EQ(larger.status, tsm::solver::Status::converged) << larger.message;
}

TEST(ContactResting, ABeamLiftedOffTheEdgesItRestsOnFailsSayingNothingHoldsIt) {
  // Loaded upwards it leaves both edges (the contacts would pull): then nothing holds it, and
  // the run says so rather than only that the unbalanced force blew up.
  tsm::Model model;
  const RunResult r = run(beam_on_knife_edges(1e3, 1), model);
  EXPECT_NE(r.status, tsm::solver::Status::converged);
  EXPECT_NE(r.message.find("held only by the contacts resting on it"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("let go: nothing else supports it"), std::string::npos) << r.message;
}

TEST(ContactResting, PushedThroughBetweenTheEdgesTheLoadPassesAMaximumThatArcLengthFollows) {
  // 5 MN: the beam sags and slides in between the edges, so the load it carries has a maximum
  // (481 kN at a sag of 1.8 m). Load control fails there and says why — the tangent lost its
  // positive definiteness within the step; arc-length control passes the maximum and follows
  // the beam down until it slides off the edges (their contacts reach its free ends).
  tsm::Model model;
  const RunResult loaded = run(beam_on_knife_edges(-5e6, 10), model);
  ASSERT_NE(loaded.status, tsm::solver::Status::converged);
  EXPECT_NE(loaded.message.find("the load seems to have reached a maximum (a limit point"), std::string::npos)
      << loaded.message;
  json m = beam_on_knife_edges(-5e6, 1);
  m["analysis"]["control"] = {{"type", "arc-length"}, {"initial_increment", 0.1}, {"max_steps", 300},
                              {"until", {{"node", 3}, {"dof", "uy"}, {"value", -2.5}}}};
  const RunResult arc = run(m, model);
  ASSERT_EQ(arc.status, tsm::solver::Status::converged) << arc.message;
  ASSERT_EQ(arc.limit_points.size(), 1u);
  EXPECT_TRUE(arc.limit_points[0].maximum);
  double largest = 0.0;
  for (const StepRecord& s : loaded.steps)
    if (s.converged) largest = std::max(largest, s.load_factor);
  // Load control stops at the maximum (its last steps cut back to 1/1024 of a step), which the
  // arc-length path brackets between its steps.
  EXPECT_NEAR(largest, arc.limit_points[0].load_factor, 5e-3 * arc.limit_points[0].load_factor);
  EXPECT_LT(arc.steps.back().load_factor, arc.limit_points[0].load_factor);  // past it, going down
  for (size_t k = 0; k < 2; ++k) EXPECT_NEAR(contact_of(arc.steps.back(), k).force, contact_of(arc.steps.back(), 0).force, 1e-6 * contact_of(arc.steps.back(), 0).force);
  // Further down it slides off the edges (their points reach its free ends at a sag of ~3 m),
  // and the run says so.
  m["analysis"]["control"]["until"]["value"] = -4.0;
  const RunResult off = run(m, model);
  ASSERT_NE(off.status, tsm::solver::Status::converged);
  EXPECT_NE(off.message.find("has slid off the beam's end: nothing else supports it"), std::string::npos) << off.message;
}

/// Two overlapping cantilevers of 2 m (EB, 20 elements each): the lower clamped at (0, 0), the
/// upper at (3, 0.05) with its free tip, node 4, at (1, 0.05) pushed down by 6 MN in 20 steps; the
/// upper tip may touch the lower beam, and the lower tip, node 2, the upper.
json overlapping_cantilevers() {
  json m = {{"materials", {{"steel", {{"E", 2.05e11}, {"nu", 0.3}}}}},
            {"sections", {{"bar", {{"A", 1e-3}, {"I", 1e-6}}}}},
            {"nodes", json::array({{{"id", 1}, {"x", 0.0}, {"y", 0.0}}, {{"id", 2}, {"x", 2.0}, {"y", 0.0}},
                                   {{"id", 3}, {"x", 3.0}, {"y", 0.05}}, {{"id", 4}, {"x", 1.0}, {"y", 0.05}}})},
            {"supports", json::array({{{"node", 1}, {"type", "fixed"}}, {{"node", 3}, {"type", "fixed"}}})},
            {"loads", json::array({{{"node", 4}, {"fy", -6e6}}})},
            {"contacts", json::array({{{"node", 4}, {"members", {0}}}, {{"node", 2}, {"members", {1}}}})},
            {"analysis", {{"control", {{"type", "load"}, {"steps", 20}}}}}};
  const auto member = [](int from, int to) {
    return json{{"from", from}, {"to", to}, {"divisions", 20}, {"element", "euler-bernoulli"}, {"material", "steel"}, {"section", "bar"}};
  };
  m["members"] = json::array({member(1, 2), member(3, 4)});
  return m;
}

TEST(ContactResting, ACantileverPressedOntoACantileverSlidesOffAtAMaximumThatLoadControlNames) {
  // Two overlapping cantilevers of 2 m (EB, 20 elements each): the lower clamped at (0, 0), the
  // upper at (3, 0.05) with its free tip at (1, 0.05), pushed down by 6 MN in 20 steps; each tip
  // may touch the other beam. The upper tip lands on the lower beam and slides along it towards
  // its free end as both bend: the load has a maximum (~157 kN), past which the tip slides on
  // under a falling load. Load control reached it
  // with its steps cut back to the smallest size, grown again, and failed there with no halving
  // left in that attempt — which the run did not name as a limit point (it required halvings in
  // the failing attempt itself). Arc-length control passes the maximum.
  json m = overlapping_cantilevers();
  tsm::Model model;
  const RunResult loaded = run(m, model);
  ASSERT_EQ(loaded.status, tsm::solver::Status::cutback_limit) << loaded.message;
  EXPECT_NE(loaded.message.find("a step already the smallest cutback allows (1/2^10 of a nominal step)"), std::string::npos)
      << loaded.message;
  EXPECT_NE(loaded.message.find("the load seems to have reached a maximum (a limit point"), std::string::npos)
      << loaded.message;
  EXPECT_NE(loaded.steps.back().message.find("use arc-length control"), std::string::npos) << "the failed step says it too";
  double largest = 0.0;
  for (const StepRecord& s : loaded.steps)
    if (s.converged) largest = std::max(largest, s.load_factor);

  m["analysis"]["control"] = {{"type", "arc-length"}, {"initial_increment", 0.02}, {"max_steps", 200},
                              {"until", {{"node", 4}, {"dof", "uy"}, {"value", -0.7}}}};
  const RunResult arc = run(m, model);
  ASSERT_EQ(arc.status, tsm::solver::Status::converged) << arc.message;
  ASSERT_FALSE(arc.limit_points.empty());
  EXPECT_TRUE(arc.limit_points[0].maximum);
  // Load control stops within its smallest step (1/20480 of 6 MN) below the maximum, which the
  // arc-length path brackets between its steps: its largest λ lies below the maximum by up to
  // the sampling of its steps (2e-4 here; steps of 0.005 put both at 0.0261247).
  EXPECT_LE(largest, arc.limit_points[0].load_factor * (1.0 + 5e-4));
  EXPECT_NEAR(largest, arc.limit_points[0].load_factor, 2e-3 * arc.limit_points[0].load_factor);
  EXPECT_LT(arc.steps.back().load_factor, 0.9 * arc.limit_points[0].load_factor);  // past it, going down
  const tsm::solver::ContactPoint& end = contact_of(arc.steps.back());
  EXPECT_GT(end.element, 12) << "slid along the lower beam, across element ends";
  expect_equilibrium(model, arc.steps.back());
}

int beam_node_at(const tsm::Model& model, double x) {
  for (int k = 0; k < model.node_count(); ++k)
    if (std::abs(model.nodes[k].position.x() - x) < 1e-12 && model.nodes[k].position.y() == 0.0 && model.nodes[k].id != 100)
      return k;
  return -1;
}

TEST(ContactDetection, ManyContactsClosingTogetherSettleInOneLookAheadAndAFailureSaysHow) {
  // The two beams loaded in one step to the first contacts: the predictor closes 85 contacts,
  // of which one is right. Released a few per converged iterate (the outermost pulling ones),
  // the set settled in 75 iterations, beyond the default 50; the look-ahead on the tangent
  // releases the other 84 together: 9 iterations. With too few iterations the step fails, and
  // its message names the way out.
  json m = pressed_beams(-20000.0 / 10240.0, 1);
  m["analysis"]["cutback"] = false;
  tsm::Model model;
  const RunResult settled = run(m, model);
  ASSERT_EQ(settled.status, tsm::solver::Status::converged) << settled.message;
  EXPECT_LE(settled.steps.back().iterations, 12);
  int touching = 0;
  for (const tsm::solver::ContactPoint& c : settled.steps.back().contacts)
    if (c.element >= 0) {
      ++touching;
      EXPECT_GT(c.force, 0.0);
    }
  EXPECT_GE(touching, 1);
  EXPECT_LE(touching, 5);
  expect_equilibrium(model, settled.steps.back());
  m["analysis"]["max_iterations"] = 5;
  const RunResult failed = run(m, model);
  ASSERT_EQ(failed.status, tsm::solver::Status::max_iterations) << failed.message;
  EXPECT_NE(failed.message.find("so the set of contacts in touch did not settle (with 201 contact nodes it may settle "
                                "given more: analysis.max_iterations, now 5, or smaller steps)"),
            std::string::npos)
      << failed.message;
}

TEST(ContactResting, ABeamPressedOntoAFarStifferBeamAlongItsLengthLoadsItAsItsContactForcesSay) {
  // The same two beams under 2 kN/m in 10 steps, with the defaults. Found as a user: the first
  // step was cut back to λ = 0.001 and failed there, "the loads are too small against what
  // rounding leaves": a contact next to a node of the stiff beam was as stiff as that beam at its
  // point (1/c = 5e17), so rounding of its 5 cm gap alone left ±10 N in its force. Capped at 10⁴ ×
  // the top beam's elements (max_stiffness_ratio), the run converges. Checked against linear beam
  // theory: the lower beam's mid-span deflection is that of its contact forces as point loads at
  // their points (bending and shear, to the geometric effects of a 6 cm sag: 1e-3), and the
  // supports carry the load.
  json m = pressed_beams(-2000.0, 10);
  tsm::Model model;
  const RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  const StepRecord& last = r.steps.back();
  const double L = 10.0, EI = 2e11 * 2e-5, GAs = 2e11 / 2.6 * 3.3e-3;
  double predicted = 0.0, pressing = 0.0;
  int touching = 0;
  for (const tsm::solver::ContactPoint& c : last.contacts) {
    if (c.element < 0) continue;
    ++touching;
    EXPECT_GT(c.force, 0.0);
    const tsm::Element& e = model.elements[c.element];
    const double xi = model.nodes[e.start].position.x() + last.displacements[tsm::dofs_per_node * e.start];
    const double xj = model.nodes[e.end].position.x() + last.displacements[tsm::dofs_per_node * e.end];
    const double a = std::min(xi + c.alpha * (xj - xi), L - (xi + c.alpha * (xj - xi)));
    predicted += c.force * (a * (3.0 * L * L - 4.0 * a * a) / (48.0 * EI) + a / (2.0 * GAs));
    pressing += c.force;
  }
  EXPECT_GT(touching, 100) << "the top beam lies on the lower one over most of its length";
  const int middle = beam_node_at(model, 5.0);
  EXPECT_NEAR(-last.displacements[tsm::dofs_per_node * middle + 1], predicted, 1e-3 * predicted);
  const auto vertical = [&](int id) { return last.reactions[tsm::dofs_per_node * model.node_index(id) + 1]; };
  EXPECT_NEAR(vertical(1) + vertical(2), pressing, 2e-3 * pressing) << "the contact forces, tilted by the slopes";
  EXPECT_NEAR(vertical(1) + vertical(2) + vertical(3) + vertical(4), 2000.0 * 9.99, 1e-6 * 2000.0 * 9.99);
  expect_equilibrium(model, last);
}

TEST(ContactResting, AColumnPushedAgainstARigidWallCarriesTheRestOfTheLoad) {
  // A cantilever column (2 m, 20 elements, EI 2e5) pushed sideways at its tip by 100 kN against a
  // wall 2 cm away, modelled as a member 10⁶ × stiffer (I = 1 m⁴, fixed at both ends): the wall
  // takes the load less what the column's tip stiffness 3EI/L³ holds at 2 cm, and the tip stays
  // at the wall (to the cap's compliance, 5e-9 m). With the contact as stiff as the wall at its
  // point, rounding stopped the run at 7.6 % of the load ("the loads are too small …").
  json m = {{"materials", {{"steel", {{"E", 2e11}, {"nu", 0.3}}}}},
            {"sections", {{"s", {{"A", 1e-3}, {"I", 1e-6}}}, {"wall", {{"A", 1.0}, {"I", 1.0}}}}},
            {"nodes", json::array({{{"id", 1}, {"x", 0.0}, {"y", 0.0}}, {{"id", 2}, {"x", 0.0}, {"y", 2.0}},
                                   {{"id", 10}, {"x", 0.02}, {"y", 1.0}}, {{"id", 11}, {"x", 0.02}, {"y", 3.0}}})},
            {"members", json::array({{{"from", 1}, {"to", 2}, {"divisions", 20}, {"material", "steel"}, {"section", "s"}},
                                     {{"from", 10}, {"to", 11}, {"divisions", 10}, {"material", "steel"}, {"section", "wall"}}})},
            {"supports", json::array({{{"node", 1}, {"type", "fixed"}}, {{"node", 10}, {"type", "fixed"}}, {{"node", 11}, {"type", "fixed"}}})},
            {"loads", json::array({{{"node", 2}, {"fx", 1e5}}})},
            {"contacts", json::array({{{"node", 2}, {"members", {1}}}})},
            {"analysis", {{"control", {{"type", "load"}, {"steps", 10}}}}}};
  tsm::Model model;
  const RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  const StepRecord& last = r.steps.back();
  const double column = 3.0 * 2e11 * 1e-6 * 0.02 / 8.0;  // 1.5 kN; the tip's turn (0.015) changes it by ~2e-4
  EXPECT_NEAR(contact_of(last).force, 1e5 - column, 1e-4 * 1e5);
  EXPECT_NEAR(node_displacement(model, last, 2)[0], 0.02, 1e-7);
  expect_equilibrium(model, last);
}

TEST(ContactDetection, DisplacementControlOfADofReachedOnlyThroughAnOpenContactFailsAtOnceSayingSo) {
  // The two beams, the lower beam's mid-span uy controlled: the load on the upper beam reaches it
  // only once the contacts close, so at the start the dof does not move under the load. Ten
  // cutbacks could not change that (the tangent at the step's start is the same); the run now
  // stops at once, "singular", and says what to control instead.
  json m = pressed_beams(-2000.0, 10);
  m["analysis"]["control"] = {{"type", "displacement"}, {"node", {5.0, 0.0}}, {"dof", "uy"}, {"target", -0.05}, {"steps", 10}};
  tsm::Model model;
  const RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::singular) << r.message;
  ASSERT_EQ(r.steps.size(), 1u);
  EXPECT_EQ(r.steps[0].cutbacks, 0);
  EXPECT_NE(r.message.find("the controlled dof does not move under the load (if the load reaches it only through a "
                           "contact still open, it does not until that closes"),
            std::string::npos)
      << r.message;
}

TEST(ContactDetection, APusherThatSlidesOffAFreeEndIsNoted) {
  // A rigid pusher 5 mm under a 2 m cantilever (10 elements) moves 1.5 m along it and 3 cm up in
  // 31 steps: it lifts the beam, slides along it across element ends and off its free end, and
  // lets go there. (Found as two overlapping cantilevers under load control, one step jumping past
  // the maximum to the upper tip hanging past the lower beam's end, silently.)
  json m = {{"materials", {{"steel", {{"E", 2e11}, {"nu", 0.3}}}}},
            {"sections", {{"s", {{"A", 1e-3}, {"I", 1e-6}}}}},
            {"nodes", json::array({{{"id", 1}, {"x", 0.0}, {"y", 0.0}}, {{"id", 2}, {"x", 2.0}, {"y", 0.0}},
                                   {{"id", 9}, {"x", 1.0}, {"y", -0.005}}})},
            {"members", json::array({{{"from", 1}, {"to", 2}, {"divisions", 10}, {"material", "steel"}, {"section", "s"}}})},
            {"supports", json::array({{{"node", 1}, {"type", "fixed"}}, {{"node", 9}, {"fix", {"rz"}}}})},
            {"prescribed", json::array({{{"node", 9}, {"ux", 1.5}, {"uy", 0.03}}})},
            {"contacts", json::array({{{"node", 9}, {"members", {0}}}})},
            {"analysis", {{"control", {{"type", "load"}, {"steps", 31}}}}}};
  tsm::Model model;
  const RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  int let_go = -1;
  for (const StepRecord& s : r.steps)
    if (s.converged && let_go < 0 && !s.slid_off.empty()) let_go = s.step;
  ASSERT_GT(let_go, 1);
  EXPECT_EQ(r.steps[let_go - 2].contacts.at(0).element, 9) << "on the last element the step before";
  EXPECT_LT(r.steps[let_go - 1].contacts.at(0).element, 0);
  std::string said;
  for (const std::string& note : r.notes)
    if (note.find("slid off") != std::string::npos) said = note;
  EXPECT_EQ(said, "the contact of node 9 slid off the free end of member 0 (past element 10's end) and let go in step " +
                      std::to_string(let_go));
}

TEST(ContactResting, ACantileverTipRestingOnABeamSharesTheLoadAsTwoSpringsInSeries) {
  // A cantilever (5.1 m) whose tip is drawn at the gap (0.1 m) above a simply supported beam
  // (span 6 m, the tip 3.1 m from its pin), tip load P in one step: the two members act as
  // springs in series, the contact carrying P c_c / (c_c + c_b) with c_c = L³/3EI + L/GA_s and
  // c_b = a²b²/3EIL + ab/(L GA_s) (Timoshenko) — to the geometric effects of a 1 mm deflection.
  json m = {{"materials", {{"steel", {{"E", 2e11}, {"G", 7.7e10}}}}},
            {"sections", {{"s", {{"A", 0.004}, {"I", 2e-5}, {"shear_area", 0.002}}}}},
            {"nodes", json::array({{{"id", 1}, {"x", 2.0}, {"y", 0.0}}, {{"id", 2}, {"x", 8.0}, {"y", 0.0}},
                                   {{"id", 11}, {"x", 0.0}, {"y", 0.1}}, {{"id", 12}, {"x", 5.1}, {"y", 0.1}}})},
            {"supports", json::array({{{"node", 1}, {"type", "pinned"}}, {{"node", 2}, {"type", "roller-x"}},
                                      {{"node", 11}, {"type", "fixed"}}})},
            {"loads", json::array({{{"node", 12}, {"fy", -1e3}}})},
            {"contacts", json::array({{{"node", 12}, {"members", {0}}, {"gap", 0.1}}})},
            {"analysis", {{"control", {{"type", "load"}, {"steps", 1}}}}}};
  const auto member = [](int from, int to, int divisions) {
    return json{{"from", from}, {"to", to}, {"divisions", divisions}, {"element", "timoshenko"}, {"material", "steel"}, {"section", "s"}};
  };
  m["members"] = json::array({member(1, 2, 12), member(11, 12, 10)});
  tsm::Model model;
  const RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  const double EI = 2e11 * 2e-5, GAs = 7.7e10 * 2e-3, Lc = 5.1, a = 3.1, b = 2.9, L = 6.0, P = 1e3;
  const double cc = Lc * Lc * Lc / (3.0 * EI) + Lc / GAs, cb = a * a * b * b / (3.0 * EI * L) + a * b / (L * GAs);
  EXPECT_NEAR(contact_of(r.steps.back()).force, P * cc / (cc + cb), 1e-5 * P);
  expect_equilibrium(model, r.steps.back());
}

TEST(ContactResting, AMatLyingOnABeamPassesItsLoadOnAsADistributedLoad) {
  // A flexible mat (67 elements, I = 1e-8) drawn at the gap above a simply supported beam (10 m,
  // 200 elements), every mat node a contact node on the beam (one entry: "nodes": {"members":
  // [1]}), the mat held across by one ux only, under 2 kN/m over its 9.99 m in 5 steps. All 68
  // nodes rest on the beam and press it; the beam's supports carry the whole load and its
  // mid-span deflection is that of the distributed load, 5wL⁴/384EI with w = 2 kN/m × 9.99/10 —
  // to the spacing of the 68 point loads, 1e-3.
  json m = {{"materials", {{"steel", {{"E", 2e11}, {"nu", 0.3}}}}},
            {"sections", {{"beam", {{"A", 4e-3}, {"I", 2e-5}}}, {"mat", {{"A", 1e-3}, {"I", 1e-8}}}}},
            {"nodes", json::array({{{"id", 1}, {"x", 0.0}, {"y", 0.0}}, {{"id", 2}, {"x", 10.0}, {"y", 0.0}},
                                   {{"id", 3}, {"x", 0.005}, {"y", 0.05}}, {{"id", 4}, {"x", 9.995}, {"y", 0.05}}})},
            {"members", json::array({{{"from", 1}, {"to", 2}, {"divisions", 200}, {"material", "steel"}, {"section", "beam"}},
                                     {{"from", 3}, {"to", 4}, {"divisions", 67}, {"material", "steel"}, {"section", "mat"},
                                      {"load", {{"fy", -2000.0}}}}})},
            {"supports", json::array({{{"node", 1}, {"type", "pinned"}}, {{"node", 2}, {"type", "roller-x"}},
                                      {{"node", 3}, {"fix", {"ux"}}}})},
            {"contacts", json::array({{{"nodes", {{"members", {1}}}}, {"members", {0}}, {"gap", 0.05}}})},
            {"analysis", {{"control", {{"type", "load"}, {"steps", 5}}}, {"output", "last"}}}};
  tsm::Model model;
  const RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  const StepRecord& last = r.steps.back();
  ASSERT_EQ(last.contacts.size(), 68u);
  for (const tsm::solver::ContactPoint& c : last.contacts) {
    EXPECT_GE(c.element, 0);
    EXPECT_GT(c.force, 0.0);
  }
  const double total = 2000.0 * 9.99, EI = 2e11 * 2e-5;
  const double carried = last.reactions[tsm::dofs_per_node * model.node_index(1) + 1] + last.reactions[tsm::dofs_per_node * model.node_index(2) + 1];
  EXPECT_NEAR(carried, total, 1e-6 * total);  // to the residual tolerance (1e-8 of the internal forces)
  int middle = -1;
  for (int k = 0; k < model.node_count(); ++k)
    if ((model.nodes[k].position - Eigen::Vector2d(5.0, 0.0)).norm() < 1e-9) middle = model.nodes[k].id;
  ASSERT_GE(middle, 0);
  const double expected = 5.0 * (total / 10.0) * std::pow(10.0, 4) / (384.0 * EI);
  EXPECT_NEAR(-node_displacement(model, last, middle)[1], expected, 1e-3 * expected);
  expect_equilibrium(model, last);
  // On a beam 5 × 10⁴ times as stiff (I = 1 m⁴) each contact would be as stiff as the beam at its
  // point; capped at 10⁴ × the mat's own elements (max_stiffness_ratio), they carry the load to
  // the beam, whose deflection is 5 × 10⁴ times smaller.
  m["sections"]["beam"]["I"] = 1.0;
  const RunResult capped = run(m, model);
  ASSERT_EQ(capped.status, tsm::solver::Status::converged) << capped.message;
  const StepRecord& on_stiff = capped.steps.back();
  const double carried_stiff = on_stiff.reactions[tsm::dofs_per_node * model.node_index(1) + 1] +
                               on_stiff.reactions[tsm::dofs_per_node * model.node_index(2) + 1];
  EXPECT_NEAR(carried_stiff, total, 1e-6 * total);
  EXPECT_NEAR(-node_displacement(model, on_stiff, middle)[1], expected * 2e-5, 1e-2 * expected * 2e-5);
  for (const tsm::solver::ContactPoint& c : on_stiff.contacts) EXPECT_GT(c.force, 0.0);
  // Uncapped, every contact is so stiff that rounding leaves more in their forces together than
  // the load: the run says so, and that it is all of them.
  m["contacts"][0]["max_stiffness_ratio"] = 1e12;
  const RunResult stiff = run(m, model);
  ASSERT_NE(stiff.status, tsm::solver::Status::converged);
  EXPECT_NE(stiff.message.find("most of that rounding is in the forces of the 68 contacts in touch (together ±"),
            std::string::npos)
      << stiff.message;
}

TEST(ContactResting, ALoadRidingOnABeamFollowsItsInfluenceLine) {
  // A node drawn at the gap (5 cm) above a simply supported beam (10 m), its ux prescribed (1 → 9
  // m) and its uy free, pressed down by λ·10 kN: held across the beam by its contact alone (it
  // was refused as "held by no element"). At every step it rides the beam's surface: its uy is
  // the beam's deflection under a point load λP at x = 1 + 8λ,
  // P a²b²/(3EIL) + P a b/(L GA_s), and the contact carries λP — to the geometric effects
  // (the surface's slope, the gap's lever): 1e-3 here.
  json m = {{"materials", {{"steel", {{"E", 2e11}, {"G", 7.7e10}}}}},
            {"sections", {{"s", {{"A", 0.004}, {"I", 2e-5}, {"shear_area", 0.002}}}}},
            {"nodes", json::array({{{"id", 1}, {"x", 0.0}, {"y", 0.0}}, {{"id", 2}, {"x", 10.0}, {"y", 0.0}},
                                   {{"id", 9}, {"x", 1.0}, {"y", 0.05}}})},
            {"members", json::array({{{"from", 1}, {"to", 2}, {"divisions", 20}, {"element", "timoshenko"},
                                      {"material", "steel"}, {"section", "s"}}})},
            {"supports", json::array({{{"node", 1}, {"type", "pinned"}}, {{"node", 2}, {"type", "roller-x"}}})},
            {"loads", json::array({{{"node", 9}, {"fy", -1e4}}})},
            {"prescribed", json::array({{{"node", 9}, {"ux", 8.0}}})},
            {"contacts", json::array({{{"node", 9}, {"members", "all"}, {"gap", 0.05}}})},
            {"analysis", {{"control", {{"type", "load"}, {"steps", 16}}}}}};
  tsm::Model model;
  const RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  ASSERT_EQ(r.steps.size(), 16u);
  const double EI = 2e11 * 2e-5, GAs = 7.7e10 * 2e-3, L = 10.0;
  for (const StepRecord& s : r.steps) {
    const double P = 1e4 * s.load_factor, a = 1.0 + 8.0 * s.load_factor, b = L - a;
    const double deflection = P * a * a * b * b / (3.0 * EI * L) + P * a * b / (L * GAs);
    EXPECT_NEAR(node_displacement(model, s, 9)[1], -deflection, 1e-3 * deflection) << "step " << s.step;
    EXPECT_NEAR(contact_of(s).force, P, 1e-3 * P) << "step " << s.step;
    expect_equilibrium(model, s);
  }
}

TEST(ContactResting, OnlyAHeldNodeDrawnAtTheGapOffTheBeamRestsOnIt) {
  json m = beam_on_knife_edges(-1e3, 1);
  const tsm::Model model = tsm::io::read_model(m);
  EXPECT_FALSE(tsm::find_mechanism(model));
  EXPECT_TRUE(tsm::find_mechanism(model, false)) << "held only by the contacts";
  const auto resting = tsm::resting_contact(model, model.contacts[0]);
  ASSERT_TRUE(resting);
  EXPECT_EQ(resting->side, -1);  // below the beam (n is +y for a beam drawn along +x)
  EXPECT_NEAR(resting->point.x(), 1.25, 1e-12);
  EXPECT_NEAR(resting->point.y(), 0.0, 1e-12);
  json free = m;  // free both ways: its contact cannot hold it along the beam (frictionless)
  free["supports"][0] = {{"node", 7}, {"fix", {"rz"}}};
  try {
    tsm::io::read_model(free);
    ADD_FAILURE() << "a contact node free along the beam was accepted";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("node 7 is held by no element"), std::string::npos) << e.what();
  }
  for (const double y : {-0.0, -0.051, 0.06}) {  // on the axis (no side yet), beyond the gap, above beyond it
    json moved = m;
    moved["nodes"][3]["y"] = y;
    moved["supports"].push_back({{"node", 1}, {"fix", {"uy"}}});  // held anyway
    const tsm::Model other = tsm::io::read_model(moved);
    EXPECT_FALSE(tsm::resting_contact(other, other.contacts[0])) << "y " << y;
  }
}

// A beam lying on another: the lower one simply supported (pinned, roller), the upper one drawn
// 50 mm above it, its two end nodes resting on it as contact nodes (gap 50 mm) and only its
// left end's ux fixed; each end loaded down by P.
json beam_on_beam(double P) {
  json m = {{"materials", {{"steel", {{"E", 2.1e11}}}}},
            {"sections", {{"s", {{"A", 0.0012}, {"I", 1.5e-6}}}}},
            {"nodes", json::array({{{"id", 1}, {"x", 0.0}, {"y", 0.0}}, {{"id", 2}, {"x", 2.0}, {"y", 0.0}},
                                   {{"id", 10}, {"x", 0.5}, {"y", 0.05}}, {{"id", 11}, {"x", 1.5}, {"y", 0.05}}})},
            {"members", json::array({{{"from", 1}, {"to", 2}, {"divisions", 10}, {"material", "steel"}, {"section", "s"}},
                                     {{"from", 10}, {"to", 11}, {"divisions", 4}, {"material", "steel"}, {"section", "s"}}})},
            {"supports", json::array({{{"node", 1}, {"type", "pinned"}}, {{"node", 2}, {"type", "roller-x"}},
                                      {{"node", 10}, {"fix", {"ux"}}}})},
            {"loads", json::array({{{"node", 10}, {"fy", -P}}, {{"node", 11}, {"fy", -P}}})},
            {"contacts", json::array({{{"node", 10}, {"members", {0}}, {"gap", 0.05}},
                                      {{"node", 11}, {"members", {0}}, {"gap", 0.05}}})},
            {"analysis", {{"control", {{"type", "load"}, {"steps", 2}}}}}};
  return m;
}

TEST(ContactResting, ABeamLyingOnASupportedBeamIsHeldByItsRestingNodes) {
  // Before, refused as a mechanism ("free to move along y"): its resting nodes are held by no
  // support, only by their beam. Now a part that is held (the lower beam) holds, along the
  // normal, the part whose nodes rest on it. Each end carries P into the lower beam, which
  // deflects under the two loads as by P a² (3L − 4a)/6EI at a = 0.5, L = 2.
  const double P = 1e3, a = 0.5, L = 2.0, EI = 2.1e11 * 1.5e-6;
  tsm::Model model;
  const RunResult r = run(beam_on_beam(P), model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  const StepRecord& last = r.steps.back();
  for (size_t k = 0; k < 2; ++k) EXPECT_NEAR(contact_of(last, k).force, P, 1e-6 * P) << "contact " << k;
  const double expected = -P * a * a * (3 * L - 4 * a) / (6 * EI);
  for (const int node : {10, 11}) EXPECT_NEAR(node_displacement(model, last, node)[1], expected, 1e-4 * -expected);
  expect_equilibrium(model, last);
  // Without the ux the upper beam is free to slide along (frictionless); resting on one node
  // only, it is free to turn about it: both still refused, saying why.
  json free = beam_on_beam(P);
  free["supports"].erase(2);
  const std::string slides = refusal(free);
  EXPECT_NE(slides.find("is free to move along x"), std::string::npos) << "refusal: " << slides;
  json one = beam_on_beam(P);
  one["contacts"].erase(1);
  const std::string turns = refusal(one);
  EXPECT_NE(turns.find("is free to rotate"), std::string::npos) << "refusal: " << turns;
  EXPECT_NE(turns.find("the node or the beam is held"), std::string::npos) << "refusal: " << turns;
}

TEST(ContactResting, ABeamLyingOnABeamLiftedOffFailsSayingNothingHoldsIt) {
  tsm::Model model;
  const RunResult r = run(beam_on_beam(-1e3), model);  // pulled up: the contacts would pull
  EXPECT_NE(r.status, tsm::solver::Status::converged);
  EXPECT_NE(r.message.find("held only by the contacts resting on it"), std::string::npos) << r.message;
}

TEST(ContactGap, ContactStartsAtTheGapAndTheForceFollowsTheClosing) {
  // A pusher 10 mm below the beam with a 4 mm gap (say, the beam's half depth): it touches after
  // 6 mm and then presses with 3EI(h − 6 mm)/a³.
  BeamSpec b;
  b.divisions = 40;
  b.A = 1e6;
  json m = pusher_model(b, 0.5125, -0.01, 0.0, 0.01 + 2e-6, 10);
  m["contacts"][0]["gap"] = 0.004;
  tsm::Model model;
  const RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  for (const StepRecord& s : r.steps) {
    const double lift = -0.01 + s.load_factor * (0.01 + 2e-6) + 0.004;  // closing beyond the gap
    const tsm::solver::ContactPoint& c = contact_of(s);
    if (lift < 0.0) {
      EXPECT_LT(c.element, 0) << "step " << s.step;
    } else {
      ASSERT_GE(c.element, 0) << "step " << s.step;
      const double a = 0.5125;
      EXPECT_NEAR(c.force, 3.0 * lift / (a * a * a), 2e-3 * 3.0 * lift / (a * a * a) + 1e-12) << "step " << s.step;
    }
  }
  EXPECT_GE(contact_of(r.steps.back()).element, 0);
}

// ---- Large push against the exact elastica with contact ----

struct PushCase {
  const char* element;
  const char* frame;  // "chord" (Eq. 6–9) or "cantilever" (FORMULATION §2b)
};

class LargePush : public ::testing::TestWithParam<PushCase> {};

TEST_P(LargePush, MatchesTheElasticaWithContact) {
  BeamSpec b;
  b.divisions = 40;
  b.A = 1e7;  // inextensible
  b.shear_area = 1e9;
  b.element = GetParam().element;
  const double a = 0.5, h = 0.3;
  tsm::Model model;
  json m = pusher_model(b, a, 0.0, 0.0, h, 30);
  m["contacts"][0]["frame"] = GetParam().frame;
  const RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  const ElasticaContact exact = elastica_with_contact(a, h);
  const tsm::solver::ContactPoint& c = contact_of(r.steps.back());
  ASSERT_GE(c.element, 0);
  std::printf("[figure] %s %s: force %.6g exact %.6g (%.2e rel), s_c %.6f exact %.6f\n", GetParam().element, GetParam().frame, c.force, exact.force, c.force / exact.force - 1.0, contact_arc_length(c, 1.0, 40), exact.arc_length);
  EXPECT_NEAR(c.force, exact.force, 0.01 * exact.force);                      // issue: within 1 %
  EXPECT_NEAR(contact_arc_length(c, 1.0, 40), exact.arc_length, 0.005);       // within 0.5 % of L
  EXPECT_GT(exact.arc_length - a, 0.02);  // the point has slid along the beam by more than an element
  for (const StepRecord& s : r.steps) expect_equilibrium(model, s);
}

INSTANTIATE_TEST_SUITE_P(Formulations, LargePush,
                         ::testing::Values(PushCase{"euler-bernoulli", "chord"}, PushCase{"timoshenko", "chord"},
                                           PushCase{"euler-bernoulli", "cantilever"}, PushCase{"timoshenko", "cantilever"}));

// ---- Sliding across element ends ----

class AcrossElementEnds : public ::testing::TestWithParam<PushCase> {};

TEST_P(AcrossElementEnds, EveryStepConvergesAndThePointMovesMonotonically) {
  // The pusher presses the beam down slightly while travelling from x = 0.2 to x = 0.8 along it:
  // the contact point crosses 12 element ends of a 20-element mesh.
  BeamSpec b;
  b.divisions = 20;
  b.A = 1e5;
  b.element = GetParam().element;
  tsm::Model model;
  json m = pusher_model(b, 0.2, 0.0, 0.6, 0.05, 30);
  m["contacts"][0]["frame"] = GetParam().frame;
  const RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  double previous_position = -1.0;
  int previous_element = -1, crossed = 0;
  for (const StepRecord& s : r.steps) {
    ASSERT_TRUE(s.converged);
    EXPECT_EQ(s.cutbacks, 0) << "step " << s.step;
    const tsm::solver::ContactPoint& c = contact_of(s);
    ASSERT_GE(c.element, 0) << "step " << s.step;
    EXPECT_GE(c.element, previous_element);
    crossed += previous_element >= 0 ? c.element - previous_element : 0;
    const double position = contact_arc_length(c, 1.0, 20);
    EXPECT_GT(position, previous_position) << "step " << s.step;
    EXPECT_GT(c.force, 0.0);
    previous_position = position;
    previous_element = c.element;
    expect_equilibrium(model, s);
  }
  EXPECT_GE(crossed, 10);
}

INSTANTIATE_TEST_SUITE_P(Formulations, AcrossElementEnds,
                         ::testing::Values(PushCase{"euler-bernoulli", "chord"}, PushCase{"timoshenko", "chord"},
                                           PushCase{"euler-bernoulli", "cantilever"}, PushCase{"timoshenko", "cantilever"}));

TEST(AcrossMembers, ThePointPassesAJointBetweenTwoMembers) {
  // The beam is two members meeting at x = 0.5 with a 3° kink (the second one drawn from its far
  // end, so its chord and normal point the other way): the contact crosses the joint.
  BeamSpec b;
  b.divisions = 10;
  b.A = 1e5;
  json m = pusher_model(b, 0.2, 0.0, 0.6, 0.05, 30);
  const double kink = 0.5 * std::tan(3.0 * std::numbers::pi / 180.0);
  m["nodes"].push_back({{"id", 3}, {"x", 0.5}, {"y", 0.0}});
  m["nodes"][1]["y"] = kink;
  m["members"] = json::array({{{"from", 1}, {"to", 3}, {"divisions", 10}, {"material", "m"}, {"section", "s"}},
                              {{"from", 2}, {"to", 3}, {"divisions", 10}, {"material", "m"}, {"section", "s"}}});
  tsm::Model model;
  const RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  bool on_first = false, on_second = false;
  for (const StepRecord& s : r.steps) {
    const tsm::solver::ContactPoint& c = contact_of(s);
    ASSERT_GE(c.element, 0) << "step " << s.step;
    EXPECT_GT(c.force, 0.0) << "step " << s.step;
    (model.elements[c.element].member == 0 ? on_first : on_second) = true;
    if (model.elements[c.element].member == 1) {
      EXPECT_TRUE(on_first);
    }
    expect_equilibrium(model, s);
  }
  EXPECT_TRUE(on_first && on_second);
}

// ---- A point resting on a beam node (not supported yet: CHANGELOG) ----

/// A pinned–pinned beam (10 m, steel) of `divisions` elements and a rigid pusher node 100 above
/// mid-span at height y0, moved down by `push` (its x held).
json simply_supported_push(int divisions, const char* element, double y0, double push, int steps) {
  BeamSpec b{.L = 10.0, .E = 2.0e11, .G = 7.7e10, .A = 4.0e-3, .I = 2.0e-5, .shear_area = 2.0e-3,
             .divisions = divisions, .element = element};
  json m = pusher_model(b, 5.0, y0, 0.0, push, steps);
  m["supports"] = json::array({{{"node", 1}, {"type", "pinned"}}, {{"node", 2}, {"type", "pinned"}},
                               {{"node", 100}, {"fix", json::array({"ux", "rz"})}}});
  return m;
}

/// The index of the beam node at (x, 0) (not the pusher, node 100).
class ContactOnANode : public ::testing::TestWithParam<const char*> {};

TEST_P(ContactOnANode, ASymmetricPushOnABeamNodeRestsOnBothElementsWithTheLinearForce) {
  // A push exactly on the mid-span node of 20 elements: on either element alone the force,
  // normal to its chord, pushes the point over the node onto the other (the chords meet at an
  // angle), so it rests on the node with both elements in contact (a vertex). Before the vertex
  // the run failed with "contact points keep hopping" at a push of 1 mm. A beam node under a
  // point load is exact for both element kinds, so the linear formula
  // P = δ / (L³/48EI + L/(4 G A_s)) (no shear term for Euler–Bernoulli) holds to the
  // membrane effect of a 1 mm push, ~1e-5 here.
  const bool timoshenko = std::string(GetParam()) == "timoshenko";
  const double delta = 1e-3, L = 10.0, EI = 2.0e11 * 2.0e-5, GAs = 7.7e10 * 2.0e-3;
  const double P = delta / (L * L * L / (48.0 * EI) + (timoshenko ? L / (4.0 * GAs) : 0.0));
  for (int steps : {1, 4}) {
    tsm::Model model;
    const RunResult r = run(simply_supported_push(20, GetParam(), 0.0, -delta, steps), model);
    ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
    const StepRecord& last = r.steps.back();
    const tsm::solver::ContactPoint& c = contact_of(last);
    const int middle = beam_node_at(model, 5.0);
    ASSERT_GE(c.element, 0);
    ASSERT_GE(c.partner, 0) << "a contact on one element only";
    EXPECT_EQ(model.elements[c.element].end, middle);  // reported on the element ending at the node …
    EXPECT_EQ(c.alpha, 1.0);                           // … at its end
    EXPECT_EQ(model.elements[c.partner].start, middle);
    EXPECT_NEAR(c.force, P, 1e-4 * P);
    const int pusher = model.node_index(100);
    EXPECT_NEAR(last.reactions[3 * pusher + 1], -P, 1e-4 * P);
    EXPECT_NEAR(last.reactions[3 * pusher], 0.0, 1e-9 * P);  // symmetric: no sideways push
    EXPECT_NEAR(node_displacement(model, last, model.nodes[middle].id)[1], -delta, 1e-9 * delta);
    expect_equilibrium(model, last);
  }
}

TEST_P(ContactOnANode, ALargePushOnABeamNodeStaysSymmetric) {
  // The same push to 1 m (the beam stretched, the chords at the node 4° apart): the vertex holds
  // to the end, the answer mirror-symmetric, and near that of 21 elements, whose mid-span is
  // mid-element (no vertex): the meshes differ, so only to their discretisation error.
  tsm::Model model, odd_model;
  const RunResult r = run(simply_supported_push(20, GetParam(), 0.001, -1.0, 20), model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  const RunResult odd = run(simply_supported_push(21, GetParam(), 0.001, -1.0, 20), odd_model);
  ASSERT_EQ(odd.status, tsm::solver::Status::converged) << odd.message;
  const StepRecord& last = r.steps.back();
  const int left = model.node_index(1), right = model.node_index(2), pusher = model.node_index(100);
  const double force = contact_of(last).force;
  ASSERT_GE(contact_of(last).partner, 0);
  EXPECT_NEAR(last.reactions[3 * left + 1], last.reactions[3 * right + 1], 1e-9 * force);
  EXPECT_NEAR(last.reactions[3 * left], -last.reactions[3 * right], 1e-9 * force);
  EXPECT_NEAR(last.reactions[3 * pusher], 0.0, 1e-9 * force);
  EXPECT_NEAR(force, contact_of(odd.steps.back()).force, 0.015 * force);
  for (const StepRecord& s : r.steps) expect_equilibrium(model, s);
}

INSTANTIATE_TEST_SUITE_P(Kinds, ContactOnANode, ::testing::Values("euler-bernoulli", "timoshenko"));

TEST(ContactOnANode, AContactOnAFarStifferMemberIsCappedOrNamedAsTooStiffToResolve) {
  // A post (A 1e-3, 0.5 m, clamped at its top) whose foot rests at the gap on the middle node of
  // a slab clamped at both ends (2 m, 20 elements, I = 1 m⁴: 10⁷ × the post's), 10 kN on the
  // foot. At a beam node the contact's compliance is the floor the contact's `edge` sets, on the
  // slab's EI: 1/c ≈ 6e20, so rounding of the coordinates alone leaves ~10⁴ N in its force —
  // unresolvable. The contact's stiffness cap (max_stiffness_ratio, 10⁴ × the post's element's
  // EA/l by default) keeps it resolvable: the contact carries what the two springs in series
  // give, the slab's 192EI/L³ against the post's EA/L, to the cap's own compliance (1/(2e13), 2e-5
  // of the post's). Uncapped, the run said only that the loads were too small (found squeezing
  // a ring between stiff plates); it now names the contact, its stiffness and the edge; with
  // edge 0.1 the floor is 10⁶ × softer and it converges.
  json m = {{"materials", {{"steel", {{"E", 2e11}, {"nu", 0.3}}}}},
            {"sections", {{"post", {{"A", 1e-3}, {"I", 1e-7}}}, {"slab", {{"A", 0.1}, {"I", 1.0}}}}},
            {"nodes", json::array({{{"id", 1}, {"x", 0.0}, {"y", 0.0}}, {{"id", 2}, {"x", 2.0}, {"y", 0.0}},
                                   {{"id", 3}, {"x", 1.0}, {"y", 0.51}}, {{"id", 4}, {"x", 1.0}, {"y", 0.01}}})},
            {"members", json::array({{{"from", 1}, {"to", 2}, {"divisions", 20}, {"material", "steel"}, {"section", "slab"}},
                                     {{"from", 3}, {"to", 4}, {"divisions", 5}, {"material", "steel"}, {"section", "post"}}})},
            {"supports", json::array({{{"node", 1}, {"type", "fixed"}}, {{"node", 2}, {"type", "fixed"}},
                                      {{"node", 3}, {"type", "fixed"}}})},
            {"loads", json::array({{{"node", 4}, {"fy", -1e4}}})},
            {"contacts", json::array({{{"node", 4}, {"members", {0}}, {"gap", 0.01}}})},
            {"analysis", {{"control", {{"type", "load"}, {"steps", 1}}}}}};
  tsm::Model model;
  const double k_slab = 192.0 * 2e11 * 1.0 / 8.0, k_post = 2e11 * 1e-3 / 0.5, P = 1e4;
  const RunResult capped = run(m, model);
  ASSERT_EQ(capped.status, tsm::solver::Status::converged) << capped.message;
  EXPECT_NEAR(contact_of(capped.steps.back()).force, P * k_slab / (k_slab + k_post), 1e-4 * P);
  m["contacts"][0]["max_stiffness_ratio"] = 1e12;
  const RunResult stiff = run(m, model);
  ASSERT_NE(stiff.status, tsm::solver::Status::converged);
  EXPECT_NE(stiff.message.find("most of that rounding is in the force of the contact at node 4"), std::string::npos)
      << stiff.message;
  EXPECT_NE(stiff.message.find("the point is at a beam node, where the contact's \"edge\" sets that compliance"),
            std::string::npos)
      << stiff.message;
  m["contacts"][0]["edge"] = 0.1;
  const RunResult softened = run(m, model);
  ASSERT_EQ(softened.status, tsm::solver::Status::converged) << softened.message;
  EXPECT_NEAR(contact_of(softened.steps.back()).force, P * k_slab / (k_slab + k_post), 1e-4 * P);
  // A ratio of 10¹¹ caps it at 1/c = 2e20, below the edge's 6e20 but still beyond what rounding
  // resolves (10¹⁰ converges): the message names the cap.
  m["contacts"][0].erase("edge");
  m["contacts"][0]["max_stiffness_ratio"] = 1e11;
  const RunResult at_cap = run(m, model);
  ASSERT_NE(at_cap.status, tsm::solver::Status::converged);
  EXPECT_NE(at_cap.message.find("(1/c = 2e+20; a member far stiffer than what presses on it makes it so): that is the "
                                "contact's cap, \"max_stiffness_ratio\" times the stiffest element holding its node"),
            std::string::npos)
      << at_cap.message;
}

TEST(ContactOnANode, AStiffContactAtANodeOfShortElementsIsNotAcceptedUnconverged) {
  // examples/contact-push.json's cantilever with 10,000 elements (0.9 mm): the pusher starts on
  // a beam node, pushed 5 mm in one step. Held at that node by both elements, the contact is so
  // stiff (compliance ~1e-23 m/N) that Newton's corrections fell to rounding level with the
  // residual still at 0.5 of the load, and the step ended "on round-off" with 2.6× the force.
  // Round-off now needs a relative residual below 1e-3: the step is cut back and converges to
  // the linear answer P = δ / (a³/3EI + a/GA_s) (the membrane effect of 5 mm: ~1e-5).
  BeamSpec b{.L = 9.0, .E = 2.05e11, .G = 7.9e10, .A = 1e-2, .I = 1e-4, .shear_area = 8.3e-3, .divisions = 10000,
             .element = "timoshenko"};
  tsm::Model model;
  const RunResult r = run(pusher_model(b, 4.05, 0.0, 0.0, 0.005, 1), model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  for (const StepRecord& s : r.steps) EXPECT_LT(s.residual_norms.back(), 1e-3) << "step " << s.step << " (" << criterion_name(s.criterion) << ")";
  const double a = 4.05, P = 0.005 / (a * a * a / (3.0 * 2.05e11 * 1e-4) + a / (7.9e10 * 8.3e-3));
  EXPECT_NEAR(contact_of(r.steps.back()).force, P, 1e-4 * P);
}

TEST_P(ContactOnANode, ThePushedBeamReturnsAndTheVertexOpensAsAWhole) {
  // Pushed down 0.5 m onto the node and back up (λ: 0 → 1 → 0): the beam is elastic, so on the
  // way back each λ gives the way down's force; the vertex holds until the pusher is back above
  // the straight beam, where both its elements would pull and it opens as a whole.
  tsm::Model model;
  json m = simply_supported_push(20, GetParam(), 0.001, -0.5, 10);
  m["analysis"]["control"]["path"] = {1.0, 0.0};
  const RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  ASSERT_EQ(r.steps.size(), 20u);
  for (int k = 0; k < 9; ++k) {  // step k+1 down and step 19−k up are at the same λ
    const StepRecord &down = r.steps[k], &up = r.steps[18 - k];
    ASSERT_NEAR(down.load_factor, up.load_factor, 1e-12);
    if (down.load_factor * 0.5 <= 0.001) continue;  // not touching yet
    ASSERT_GE(contact_of(down).partner, 0) << "step " << down.step;
    ASSERT_GE(contact_of(up).partner, 0) << "step " << up.step;
    EXPECT_NEAR(contact_of(up).force, contact_of(down).force, 1e-6 * contact_of(down).force) << "step " << up.step;
  }
  const StepRecord& last = r.steps.back();
  EXPECT_LT(contact_of(last).element, 0);
  EXPECT_LT(last.displacements.cwiseAbs().maxCoeff(), 1e-9);
}

// ---- Many short elements ----

TEST(FineMesh, APushSlidingOverManyShortElementsTakesFewIteratesPerStep) {
  // The contact-push example on a mesh of 4.5 mm Timoshenko elements: the point slides over
  // ~30 elements a step, and with Ψ = EI/(G A_s) ~ 1500 l0² the contact element is far stiffer
  // than the beam around it. The sliding terms join the solve only near the solution
  // (newton.cpp, sliding_terms_below): with them in every solve the point hopped between
  // elements, 8–21 iterates a step and a cutback. The answer is that of the quasi-Newton variant
  // (sliding terms never used, converging by another path).
  BeamSpec b{.L = 9.0, .E = 2.05e11, .G = 7.9e10, .A = 1e-2, .I = 1e-4, .shear_area = 8.3e-3, .divisions = 2000,
             .element = "timoshenko"};
  json m = pusher_model(b, 4.05, 0.0, 0.0, 1.0, 10);
  tsm::Model model, quasi_model;
  const RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  ASSERT_EQ(r.steps.size(), 10u);
  int total = 0;
  for (const StepRecord& s : r.steps) {
    EXPECT_EQ(s.cutbacks, 0) << "step " << s.step;
    EXPECT_LE(s.iterations, 12) << "step " << s.step;
    total += s.iterations;
    expect_equilibrium(model, s);
  }
  std::printf("[figure] 2000-element push: %d iterates in 10 steps\n", total);
  EXPECT_LE(total, 80);
  m["contacts"][0]["sliding_tangent"] = false;
  const RunResult quasi = run(m, quasi_model);
  ASSERT_EQ(quasi.status, tsm::solver::Status::converged) << quasi.message;
  const tsm::solver::ContactPoint &c = contact_of(r.steps.back()), &q = contact_of(quasi.steps.back());
  EXPECT_NEAR(contact_arc_length(c, 9.0, 2000), contact_arc_length(q, 9.0, 2000), 1e-9);
  EXPECT_NEAR(c.force, q.force, 1e-6 * q.force);
  EXPECT_GT(contact_arc_length(c, 9.0, 2000) - 4.05, 0.1);  // slid over more than 20 elements
}

// ---- Release ----

TEST(ContactRelease, PullingBackReleasesAtZeroForceAndTheBeamReturnsStraight) {
  // Pusher 0.0123 below the beam, pushed 0.05 up and back down (λ: 0 → 1 → 0).
  BeamSpec b;
  b.divisions = 20;
  b.A = 1e6;
  tsm::Model model;
  json m = pusher_model(b, 0.6, -0.0123, 0.0, 0.05, 20);
  m["analysis"]["control"]["path"] = {1.0, 0.0};
  const RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  ASSERT_EQ(r.steps.size(), 40u);
  const double flexibility = 0.6 * 0.6 * 0.6 / 3.0;  // EI = 1
  int active_steps = 0;
  for (const StepRecord& s : r.steps) {
    const double lift = 0.05 * s.load_factor - 0.0123;  // pusher above the straight beam
    const tsm::solver::ContactPoint& c = contact_of(s);
    if (lift < 0.0) {
      EXPECT_LT(c.element, 0) << "step " << s.step << ": in contact while below the beam";
      EXPECT_LT(s.displacements.cwiseAbs().maxCoeff(), 1e-12 + 0.06) << "step " << s.step;
      // only the pusher moves; the beam is straight
      for (int k = 0; k < model.node_count(); ++k)
        if (model.nodes[k].id != 100) EXPECT_LT(s.displacements.segment<3>(3 * k).norm(), 1e-12) << "node " << model.nodes[k].id;
    } else {
      ++active_steps;
      ASSERT_GE(c.element, 0) << "step " << s.step;
      // Small lifts: the force follows the linear law down to zero (within geometric effects).
      if (lift < 0.005) EXPECT_NEAR(c.force, lift / flexibility, 2e-3 * lift / flexibility) << "step " << s.step;
    }
  }
  EXPECT_EQ(active_steps, 2 * 16 - 1);  // λ = 0.25 … 1 on the way up and back down
  // Out of contact the beam carries nothing: those steps' relative residuals are rounding noise
  // (up to ~1), and the run says so once, rather than leave them to look like failures.
  int quiet = 0;
  for (const StepRecord& s : r.steps) quiet += s.criterion == tsm::solver::Criterion::nothing_carried ? 1 : 0;
  EXPECT_GT(quiet, 0);
  ASSERT_FALSE(r.notes.empty());
  EXPECT_NE(r.notes.front().find("the structure carried next to nothing"), std::string::npos) << r.notes.front();
  EXPECT_NE(r.notes.front().find(std::to_string(quiet) + " steps from"), std::string::npos) << r.notes.front();
}

// ---- A node crossing the beam within one step; two contacts; beam on beam ----

TEST(ContactDetection, ANodeCrossingTheBeamInOneStepGivesTheSameAnswerAsManySteps) {
  BeamSpec b;
  b.divisions = 20;
  b.A = 1e6;
  tsm::Model one, many;
  // Both runs converge tightly (relative residual 1e-12), so they must agree to 1e-9.
  json m1 = pusher_model(b, 0.55, -0.01, 0.0, 0.06, 1), m10 = pusher_model(b, 0.55, -0.01, 0.0, 0.06, 10);
  m1["analysis"]["tolerance"] = m10["analysis"]["tolerance"] = 1e-12;
  const RunResult a = run(m1, one);
  const RunResult c = run(m10, many);
  ASSERT_EQ(a.status, tsm::solver::Status::converged) << a.message;
  ASSERT_EQ(c.status, tsm::solver::Status::converged) << c.message;
  const auto& p = contact_of(a.steps.back());
  const auto& q = contact_of(c.steps.back());
  EXPECT_EQ(p.element, q.element);
  EXPECT_NEAR(p.alpha, q.alpha, 1e-9);
  EXPECT_NEAR(p.force, q.force, 1e-9 * q.force);
}

// ---- Many posts pressing one beam: the active set ----
// A 20 m beam, pinned at its ends, pushed up by 40 rigid posts to 0.05, 0.10, 0.15 m in turn.
// The tall posts near the ends lever the beam up and the others lose contact. Releasing every
// post that pulls at once lets some of them through the beam further on; such a post must take
// part again (before, the step failed at every cutback). Checked: every post is either in
// contact and pressing, or below the beam's deflected centre line (EB elements: the Hermite
// cubic of each element in its chord frame).

TEST(ContactDetection, ManyPostsFindTheirActiveSetWithoutPassingThroughTheBeam) {
  const int posts = 40, divisions = 40;
  const double L = 20.0;
  json m = {
      {"materials", {{"steel", {{"E", 2.05e11}}}}},
      {"sections", {{"box", {{"A", 1e-2}, {"I", 1e-4}}}}},
      {"nodes", json::array({{{"id", 1}, {"x", 0.0}, {"y", 0.0}}, {{"id", 2}, {"x", L}, {"y", 0.0}}})},
      {"members", json::array({{{"from", 1}, {"to", 2}, {"divisions", divisions}, {"material", "steel"}, {"section", "box"}}})},
      {"supports", json::array({{{"node", 1}, {"type", "pinned"}}, {{"node", 2}, {"fix", {"uy"}}}})},
      {"prescribed", json::array()},
      {"contacts", json::array()},
      {"analysis", {{"control", {{"type", "load"}, {"steps", 10}}}, {"output", "last"}}},
  };
  for (int k = 0; k < posts; ++k) {
    const int id = 100 + k;
    m["nodes"].push_back({{"id", id}, {"x", 0.3 + k * 19.4 / (posts - 1) + 0.013}, {"y", 0.0}});
    m["supports"].push_back({{"node", id}, {"fix", {"ux", "rz"}}});
    m["prescribed"].push_back({{"node", id}, {"uy", 0.05 * (1 + k % 3)}});
    m["contacts"].push_back({{"node", id}, {"members", "all"}});
  }
  tsm::Model model;
  const RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  const StepRecord& last = r.steps.back();
  ASSERT_EQ(last.load_factor, 1.0);
  int pressing = 0;
  for (int k = 0; k < posts; ++k) {
    const tsm::solver::ContactPoint& c = contact_of(last, k);
    if (c.element >= 0) {
      ++pressing;
      EXPECT_GE(c.force, 0.0) << "post " << k;
      continue;
    }
    // A released post: find the element below it and its deflected centre line there.
    const Eigen::Vector2d post = node_position(model, last, 100 + k);
    bool found = false;
    for (const tsm::Element& e : model.elements) {
      const Eigen::Vector2d a = model.nodes[e.start].position + last.displacements.segment<2>(3 * e.start);
      const Eigen::Vector2d b = model.nodes[e.end].position + last.displacements.segment<2>(3 * e.end);
      const Eigen::Vector2d t = (b - a).normalized(), n(-t.y(), t.x());
      const double l = (b - a).norm(), xi = (post - a).dot(t) / l;
      if (xi < 0.0 || xi > 1.0) continue;
      const double beta = std::atan2(b.y() - a.y(), b.x() - a.x()) - std::atan2(model.nodes[e.end].position.y() - model.nodes[e.start].position.y(),
                                                                               model.nodes[e.end].position.x() - model.nodes[e.start].position.x());
      const double ti = last.displacements[3 * e.start + 2] - beta, tj = last.displacements[3 * e.end + 2] - beta;
      const double w = l * (ti * (xi - 2 * xi * xi + xi * xi * xi) + tj * (xi * xi * xi - xi * xi));
      EXPECT_LE((post - a).dot(n), w + 1e-9 * L) << "post " << k << " is through the beam";
      found = true;
      break;
    }
    EXPECT_TRUE(found) << "post " << k << " beyond the beam";
  }
  EXPECT_GE(pressing, 2);
  EXPECT_LT(pressing, posts);  // most posts have let go
}

TEST(ContactDetection, ANodeSlidingOverManyElementsInOneStepStillTouches) {
  // A wheel rolls 10 m along a 20 m simply supported rail of 1,000 elements, pressing 5 cm into
  // it: 25 elements a step, far beyond the one element's reach around the node where its side is
  // read directly. It must touch in the first step and press on to the end (the sides are carried
  // along the member), with the force of the linear point-load formula,
  // δ = P (a²b²/(3EIL) + ab/(G A_s L)).
  BeamSpec b{.L = 20.0, .E = 2.1e11, .G = 8.1e10, .A = 7.7e-3, .I = 3e-5, .shear_area = 3.5e-3, .divisions = 1000,
             .element = "timoshenko"};
  json m = beam_model(b);
  m["nodes"].push_back({{"id", 9}, {"x", 5.0}, {"y", 0.001}});
  m["supports"] = json::array({{{"node", 1}, {"type", "pinned"}}, {{"node", 2}, {"type", "roller-x"}},
                               {{"node", 9}, {"fix", json::array({"rz"})}}});
  m["prescribed"] = json::array({{{"node", 9}, {"ux", 10.0}, {"uy", -0.051}}});
  m["contacts"] = json::array({{{"node", 9}, {"members", "all"}}});
  m["analysis"] = {{"control", {{"type", "load"}, {"steps", 20}}}};
  tsm::Model model;
  const RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  double largest = 0.0;
  for (const StepRecord& s : r.steps) {
    const tsm::solver::ContactPoint& c = contact_of(s);
    ASSERT_GE(c.element, 0) << "step " << s.step << ": the wheel went through the rail";
    const double a = 5.0 + 10.0 * s.load_factor, bb = 20.0 - a, depth = 0.051 * s.load_factor - 0.001;
    const double compliance = a * a * bb * bb / (3.0 * 2.1e11 * 3e-5 * 20.0) + a * bb / (8.1e10 * 3.5e-3 * 20.0);
    largest = std::max(largest, std::abs(c.force * compliance / depth - 1.0));
    EXPECT_NEAR(c.force, depth / compliance, 0.005 * depth / compliance) << "step " << s.step;
    EXPECT_NEAR(contact_arc_length(c, 20.0, 1000), a, 1e-3) << "step " << s.step;
  }
  std::printf("[figure] wheel on a 1000-element rail: force within %.2e of the linear formula\n", largest);
}

TEST(ContactDetection, ANodeDraggedAcrossAMemberJointInOneStepStillTouches) {
  // The same kind of pass in a beam built of two members meeting end to end (the second drawn
  // either way): a pusher dragged from 3.03 m to 7.03 m over a 10 m pinned beam, 0.3 m down, in
  // ONE step, ends 2 m past the joint at 5 m. The side it came from is carried across the joint
  // (two members meeting there and nothing else); before, it went through the beam without
  // touching. The answer is that of the same mesh drawn as one member, to round-off. With a
  // column under the joint in the contact's set (a T: the beam's top side goes on into the next
  // span's top, past the column; the pusher's side is also read off the column beyond its top,
  // left of its line, which is no side of the beam) it is that of the contact on the beam's two
  // members only, and of the same drag in 10 steps.
  const auto model_of = [](int members, bool reversed) {
    json m = {{"materials", {{"steel", {{"E", 2e11}, {"G", 7.7e10}}}}},
              {"sections", {{"s", {{"A", 0.004}, {"I", 2e-5}, {"shear_area", 0.002}}}}},
              {"nodes", json::array({{{"id", 1}, {"x", 0.0}, {"y", 0.0}}, {{"id", 2}, {"x", 5.0}, {"y", 0.0}},
                                     {{"id", 3}, {"x", 10.0}, {"y", 0.0}}, {{"id", 9}, {"x", 3.03}, {"y", 0.001}}})},
              {"supports", json::array({{{"node", 1}, {"type", "pinned"}}, {{"node", 3}, {"type", "pinned"}}})},
              {"prescribed", json::array({{{"node", 9}, {"ux", 4.0}, {"uy", -0.3}}})},
              {"contacts", json::array({{{"node", 9}, {"members", "all"}}})},
              {"analysis", {{"control", {{"type", "load"}, {"steps", 1}}}}}};
    const auto member = [](int from, int to, int divisions) {
      return json{{"from", from}, {"to", to}, {"divisions", divisions}, {"element", "timoshenko"},
                  {"material", "steel"}, {"section", "s"}};
    };
    m["members"] = members == 1 ? json::array({member(1, 3, 20)})
                                : json::array({member(1, 2, 10), reversed ? member(3, 2, 10) : member(2, 3, 10)});
    if (members == 1) m["nodes"].erase(1);
    if (members == 3) {  // a column from (5, −4) up to the joint, clamped at its foot
      m["nodes"].push_back({{"id", 4}, {"x", 5.0}, {"y", -4.0}});
      m["members"].push_back(member(4, 2, 8));
      m["supports"].push_back({{"node", 4}, {"type", "fixed"}});
    }
    return m;
  };
  tsm::Model one_model;
  const RunResult one = run(model_of(1, false), one_model);
  ASSERT_EQ(one.status, tsm::solver::Status::converged) << one.message;
  const double force = contact_of(one.steps.back()).force;
  ASSERT_GT(force, 4e5);
  for (const bool reversed : {false, true}) {
    tsm::Model model;
    const RunResult r = run(model_of(2, reversed), model);
    ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
    const tsm::solver::ContactPoint& c = contact_of(r.steps.back());
    ASSERT_GE(c.element, 0) << "the pusher went through the beam (reversed: " << reversed << ")";
    EXPECT_EQ(model.elements[c.element].member, 1);
    EXPECT_NEAR(c.force, force, 1e-8 * force) << "reversed: " << reversed;
    const int pusher = model.node_index(9), one_pusher = one_model.node_index(9);
    EXPECT_NEAR(r.steps.back().reactions[3 * pusher], one.steps.back().reactions[3 * one_pusher], 1e-8 * force);
  }
  json beam_only = model_of(3, false);
  beam_only["contacts"][0]["members"] = {0, 1};
  tsm::Model beam_model_;
  const RunResult on_beam = run(beam_only, beam_model_);
  ASSERT_EQ(on_beam.status, tsm::solver::Status::converged) << on_beam.message;
  const double supported = contact_of(on_beam.steps.back()).force;
  ASSERT_GT(supported, 2e5);
  for (const int steps : {1, 10}) {
    json tee = model_of(3, false);
    tee["analysis"]["control"]["steps"] = steps;
    tsm::Model model;
    const RunResult r = run(tee, model);
    ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
    const tsm::solver::ContactPoint& c = contact_of(r.steps.back());
    ASSERT_GE(c.element, 0) << "the pusher went through the beam (T joint, " << steps << " steps)";
    EXPECT_EQ(model.elements[c.element].member, 1);
    EXPECT_NEAR(c.force, supported, 1e-8 * supported) << steps << " steps";
  }
}

TEST(ContactDetection, ANodeDraggedIntoAColumnInOneStepStopsAtIt) {
  // A pusher pressed onto a pinned beam's top at x = 3 m and dragged 2.02 m right, 1 cm down, in
  // ONE step, towards a cross joint at 5 m (columns 2 m up and down, pinned at their ends, all in
  // the contact's set): the column standing up is in its way. The iterate puts the pusher 2 cm
  // past the joint, beyond the span of every element whose side it knows (the far span's top is
  // rightly not connected to the near span's across the column), so no element it ends within had
  // it cross: before, it went through beam and column without touching anything. Its path from
  // the converged state crosses the near span's top: contact starts there and is handed along the
  // beam into the corner, where the column's left face stops it — as in 10 steps.
  json m = {{"materials", {{"steel", {{"E", 2e11}, {"G", 7.7e10}}}}},
            {"sections", {{"s", {{"A", 0.004}, {"I", 2e-5}, {"shear_area", 0.002}}}}},
            {"nodes", json::array({{{"id", 1}, {"x", 0.0}, {"y", 0.0}}, {{"id", 2}, {"x", 10.0}, {"y", 0.0}},
                                   {{"id", 3}, {"x", 5.0}, {"y", 0.0}}, {{"id", 4}, {"x", 5.0}, {"y", 2.0}},
                                   {{"id", 5}, {"x", 5.0}, {"y", -2.0}}, {{"id", 9}, {"x", 3.0}, {"y", 0.001}}})},
            {"supports", json::array({{{"node", 1}, {"type", "pinned"}}, {{"node", 2}, {"type", "pinned"}},
                                      {{"node", 4}, {"type", "pinned"}}, {{"node", 5}, {"type", "pinned"}}})},
            {"prescribed", json::array({{{"node", 9}, {"ux", 2.02}, {"uy", -0.01}}})},
            {"contacts", json::array({{{"node", 9}, {"members", "all"}}})},
            {"analysis", {{"control", {{"type", "load"}, {"steps", 1}}}}}};
  const auto member = [](int from, int to, int divisions) {
    return json{{"from", from}, {"to", to}, {"divisions", divisions}, {"element", "timoshenko"}, {"material", "steel"}, {"section", "s"}};
  };
  m["members"] = json::array({member(1, 3, 10), member(3, 2, 10), member(3, 4, 4), member(3, 5, 4)});
  for (const int steps : {1, 10}) {
    m["analysis"]["control"]["steps"] = steps;
    tsm::Model model;
    const RunResult r = run(m, model);
    ASSERT_EQ(r.status, tsm::solver::Status::converged) << steps << " steps: " << r.message;
    const tsm::solver::ContactPoint& c = contact_of(r.steps.back());
    ASSERT_GE(c.element, 0) << "the pusher went through beam and column (" << steps << " steps)";
    // At the joint: on the near span's last element or the upper column's first, or on both.
    const int joint = model.node_index(3);
    for (const int e : {c.element, c.partner}) {
      if (e < 0) continue;
      const tsm::Element& element = model.elements[e];
      EXPECT_TRUE(element.member == 0 || element.member == 2) << steps << " steps: member " << element.member;
      EXPECT_TRUE(element.start == joint || element.end == joint) << steps << " steps: element " << e << " is not at the joint";
    }
    EXPECT_GT(c.force, 1e6) << steps << " steps: the column is pushed 2 cm at its foot";
  }
}

TEST(ContactDetection, TwoNodesPressingOneElementFailSayingSoNotThroughTheBeam) {
  // Two pushers 0.4 m apart over one 2.5 m element of a pinned beam, both pushed 10 cm down: the
  // tracker gives an element one contact element, so a node that found its element taken went
  // through the beam unnoticed. Now the step fails naming both nodes and what to do.
  json m = {{"materials", {{"steel", {{"E", 2e11}, {"G", 7.7e10}}}}},
            {"sections", {{"s", {{"A", 0.004}, {"I", 2e-5}, {"shear_area", 0.002}}}}},
            {"nodes", json::array({{{"id", 1}, {"x", 0.0}, {"y", 0.0}}, {{"id", 2}, {"x", 10.0}, {"y", 0.0}},
                                   {{"id", 8}, {"x", 3.0}, {"y", 0.001}}, {{"id", 9}, {"x", 2.6}, {"y", 0.001}}})},
            {"members", json::array({{{"from", 1}, {"to", 2}, {"divisions", 4}, {"element", "timoshenko"},
                                      {"material", "steel"}, {"section", "s"}}})},
            {"supports", json::array({{{"node", 1}, {"type", "pinned"}}, {{"node", 2}, {"type", "roller-x"}},
                                      {{"node", 8}, {"fix", {"ux"}}}, {{"node", 9}, {"fix", {"ux"}}}})},
            {"prescribed", json::array({{{"node", 8}, {"uy", -0.1}}, {{"node", 9}, {"uy", -0.1}}})},
            {"contacts", json::array({{{"node", 8}, {"members", "all"}}, {{"node", 9}, {"members", "all"}}})},
            {"analysis", {{"control", {{"type", "load"}, {"steps", 5}}}}}};
  tsm::Model model;
  const RunResult r = run(m, model);
  ASSERT_NE(r.status, tsm::solver::Status::converged) << "converged with a node through the beam";
  EXPECT_NE(r.message.find("which contact node"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("one contact per element (give that member more divisions)"), std::string::npos) << r.message;
  // With 0.25 m elements each node has elements of its own, and the answer shows why the coarse
  // run could not settle: pushed at 2.6 m the beam sags more at 3.0 m than 10 cm, so only node 9
  // touches, and node 8 ends above the beam.
  m["members"][0]["divisions"] = 40;
  const RunResult fine = run(m, model);
  ASSERT_EQ(fine.status, tsm::solver::Status::converged) << fine.message;
  EXPECT_LT(contact_of(fine.steps.back(), 0).element, 0);
  EXPECT_GE(contact_of(fine.steps.back(), 1).element, 0);
  const int under_8 = beam_node_at(model, 3.0);
  ASSERT_GE(under_8, 0);
  EXPECT_LT(node_displacement(model, fine.steps.back(), model.nodes[under_8].id)[1], -0.1);
}

TEST(ContactDetection, ANodeJustOutsideAnArchReadsItsSideOffTheElementUnderIt) {
  // A clamped half-circle arch (radius 5 m, 40 elements) and a pusher starting 0.1 mm outside it,
  // inside the sagitta of the chords (3.9 mm): just past an element's end the next chord's line
  // extended runs outside the arch, so reading the side off it said "inside", and carried round
  // the arch that side let the pusher, moved to 1 cm inside the crown in one step, go through
  // without touching. Sides are now read only off elements that hold the node, or whose
  // neighbour past that end does not; the pusher then ends as the same push made at the crown.
  const auto arch = [](double angle_from, double angle_to) {
    const double pi = std::numbers::pi, a0 = angle_from * pi / 180.0, a1 = angle_to * pi / 180.0;
    const double x0 = 5.0001 * std::cos(a0), y0 = 5.0001 * std::sin(a0), x1 = 4.99 * std::cos(a1), y1 = 4.99 * std::sin(a1);
    return json{{"materials", {{"steel", {{"E", 2e11}, {"G", 7.7e10}}}}},
                {"sections", {{"s", {{"A", 0.004}, {"I", 2e-5}, {"shear_area", 0.002}}}}},
                {"nodes", json::array({{{"id", 1}, {"x", -5.0}, {"y", 0.0}}, {{"id", 2}, {"x", 5.0}, {"y", 0.0}},
                                       {{"id", 9}, {"x", x0}, {"y", y0}}})},
                {"members", json::array({{{"from", 1}, {"to", 2}, {"divisions", 40}, {"element", "timoshenko"}, {"material", "steel"},
                                          {"section", "s"}, {"arc", {{"center", {0.0, 0.0}}, {"sweep", -pi}}}}})},
                {"supports", json::array({{{"node", 1}, {"type", "fixed"}}, {{"node", 2}, {"type", "fixed"}},
                                          {{"node", 9}, {"fix", json::array({"rz"})}}})},
                {"prescribed", json::array({{{"node", 9}, {"ux", x1 - x0}, {"uy", y1 - y0}}})},
                {"contacts", json::array({{{"node", 9}, {"members", "all"}}})},
                {"analysis", {{"control", {{"type", "load"}, {"steps", 1}}}}}};
  };
  tsm::Model pushed_model, slid_model;
  const RunResult pushed = run(arch(91.0, 91.0), pushed_model);
  ASSERT_EQ(pushed.status, tsm::solver::Status::converged) << pushed.message;
  const tsm::solver::ContactPoint& there = contact_of(pushed.steps.back());
  ASSERT_GT(there.force, 1e4);
  const RunResult slid = run(arch(126.87, 91.0), slid_model);
  ASSERT_EQ(slid.status, tsm::solver::Status::converged) << slid.message;
  const tsm::solver::ContactPoint& c = contact_of(slid.steps.back());
  ASSERT_GE(c.element, 0) << "the pusher went through the arch";
  EXPECT_EQ(c.element, there.element);
  EXPECT_NEAR(c.force, there.force, 1e-9 * there.force);
}

TEST(ContactDetection, APusherSlidingUpAnLFramesOuterFaceLeavesAtTheCorner) {
  // An L-frame (column (0,0)–(0,4) clamped, beam (0,4)–(4,4) pinned at its end, all members in
  // the contact's set) and a rigid pusher on the column's outer face, moved up 2 m and 5 cm
  // into it in 20 steps. It presses the column, is handed across the corner to the beam's top
  // (the same, outer, side) and, once above the beam's line, lets go: the frame springs back
  // unstressed. Before, it went on pressing the beam's start from inside the corner
  // (200 MN) until it failed with "contact points keep hopping".
  const auto member = [](int from, int to) {
    return json{{"from", from}, {"to", to}, {"divisions", 8}, {"element", "timoshenko"}, {"material", "steel"}, {"section", "s"}};
  };
  json m = {{"materials", {{"steel", {{"E", 2e11}, {"G", 7.7e10}}}}},
            {"sections", {{"s", {{"A", 0.01}, {"I", 1e-4}, {"shear_area", 0.005}}}}},
            {"nodes", json::array({{{"id", 1}, {"x", 0.0}, {"y", 0.0}}, {{"id", 2}, {"x", 0.0}, {"y", 4.0}},
                                   {{"id", 3}, {"x", 4.0}, {"y", 4.0}}, {{"id", 9}, {"x", -0.001}, {"y", 3.0}}})},
            {"members", json::array({member(1, 2), member(2, 3)})},
            {"supports", json::array({{{"node", 1}, {"type", "fixed"}}, {{"node", 3}, {"type", "pinned"}}})},
            {"prescribed", json::array({{{"node", 9}, {"ux", 0.05}, {"uy", 2.0}}})},
            {"contacts", json::array({{{"node", 9}, {"members", "all"}}})},
            {"analysis", {{"control", {{"type", "load"}, {"steps", 20}}}}}};
  tsm::Model model;
  const RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  bool pressed_column = false;
  for (const StepRecord& s : r.steps) {
    const tsm::solver::ContactPoint& c = contact_of(s);
    if (s.load_factor < 0.45 + 1e-12 && s.load_factor > 0.05) {
      ASSERT_GE(c.element, 0) << "step " << s.step;
      EXPECT_EQ(model.elements[c.element].member, 0) << "step " << s.step;  // on the column
      EXPECT_GT(c.force, 0.0);
      pressed_column = true;
    }
    if (s.load_factor > 0.55) {
      EXPECT_LT(c.element, 0) << "step " << s.step << ": still in contact above the beam";
      const int pusher = model.node_index(9);
      for (int k = 0; k < model.node_count(); ++k)
        if (k != pusher) EXPECT_LT(node_displacement(model, s, model.nodes[k].id).cwiseAbs().maxCoeff(), 1e-9) << "step " << s.step;
    }
  }
  EXPECT_TRUE(pressed_column);
}

TEST(ContactDetection, TwoContactsAtOnceMatchTheLinearFlexibility) {
  BeamSpec b;
  b.divisions = 40;
  b.A = 1e6;
  json m = pusher_model(b, 0.3, 0.0, 0.0, 1e-6, 1);
  m["nodes"].push_back({{"id", 101}, {"x", 0.7}, {"y", 0.0}});
  m["supports"].push_back({{"node", 101}, {"fix", {"ux", "rz"}}});
  m["prescribed"].push_back({{"node", 101}, {"uy", 4e-6}});
  m["contacts"].push_back({{"node", 101}, {"members", "all"}});
  tsm::Model model;
  const RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  // Cantilever flexibility (EI = 1): f_ij = a_i² (3 a_j − a_i) / 6 for a_i ≤ a_j.
  const double a1 = 0.3, a2 = 0.7;
  Eigen::Matrix2d F;
  F << a1 * a1 * a1 / 3.0, a1 * a1 * (3 * a2 - a1) / 6.0, a1 * a1 * (3 * a2 - a1) / 6.0, a2 * a2 * a2 / 3.0;
  const Eigen::Vector2d P = F.fullPivLu().solve(Eigen::Vector2d(1e-6, 4e-6));
  ASSERT_GT(P.minCoeff(), 0.0);
  EXPECT_NEAR(contact_of(r.steps.back(), 0).force, P[0], 1e-4 * P.norm());
  EXPECT_NEAR(contact_of(r.steps.back(), 1).force, P[1], 1e-4 * P.norm());
}

TEST(ContactDetection, BeamOnBeamMatchesTheSeriesSprings) {
  // A hanging post (clamped at its top, moved down) lands with its free bottom node on the
  // mid-span of a cantilever: the contact force compresses the post and bends the cantilever.
  BeamSpec b;
  b.divisions = 20;
  b.A = 1e6;
  json m = beam_model(b);
  m["nodes"].push_back({{"id", 10}, {"x", 0.5}, {"y", 1e-6}});
  m["nodes"].push_back({{"id", 11}, {"x", 0.5}, {"y", 0.5}});
  m["sections"]["post"] = {{"A", 2e-1}, {"I", 1.0}, {"shear_area", 1e3}};
  m["members"].push_back({{"from", 11}, {"to", 10}, {"divisions", 4}, {"material", "m"}, {"section", "post"}});
  m["supports"] = json::array({{{"node", 1}, {"type", "fixed"}}, {{"node", 11}, {"fix", {"ux", "rz"}}}});
  m["prescribed"] = json::array({{{"node", 11}, {"uy", -1.1e-5}}});
  m["contacts"] = json::array({{{"node", 10}, {"members", {0}}}});
  tsm::Model model;
  const RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  const double closing = 1e-5;                                   // 1.1e-5 minus the 1e-6 gap
  const double compliance = 0.125 / 3.0 + 0.5 / (1.0 * 2e-1);    // cantilever a³/3EI + post L/EA
  EXPECT_NEAR(contact_of(r.steps.back()).force, closing / compliance, 1e-4 * closing / compliance);
}

TEST(ContactDetection, ABeamTipDraggedAlongABeamEndsWhereAPushThereEnds) {
  // A cantilever (8 elements, from (2, 2) down to its tip just above a 20-element pinned beam at
  // x = 3.03) has its clamp moved 3 m along and 5 cm down: its tip, pressed onto the beam, slides
  // over six of the beam's nodes. Frictionless and elastic, it must end as the same cantilever
  // clamped at the end position from the start and only pushed down there. Before, the tip
  // stopped at the first beam node: the contact's blocks coupling the tip to the next element's
  // far node landed in an entry of the factor's fill, which the factorisation starts at zero,
  // so Newton ran on a tangent without them and diverged (then a pull released the contact at
  // a wild iterate, and the tip was accepted through the beam for the rest of the run).
  const auto model_of = [](double clamp_x, double move_x, int steps) {
    const auto member = [](int from, int to, int divisions) {
      return json{{"from", from}, {"to", to}, {"divisions", divisions}, {"element", "timoshenko"},
                  {"material", "steel"}, {"section", "s"}};
    };
    return json{{"materials", {{"steel", {{"E", 2e11}, {"G", 7.7e10}}}}},
                {"sections", {{"s", {{"A", 0.004}, {"I", 2e-5}, {"shear_area", 0.002}}}}},
                {"nodes", json::array({{{"id", 1}, {"x", 0.0}, {"y", 0.0}}, {{"id", 2}, {"x", 10.0}, {"y", 0.0}},
                                       {{"id", 5}, {"x", clamp_x}, {"y", 2.0}}, {{"id", 6}, {"x", clamp_x + 1.03}, {"y", 0.001}}})},
                {"members", json::array({member(1, 2, 20), member(5, 6, 8)})},
                {"supports", json::array({{{"node", 1}, {"type", "pinned"}}, {{"node", 2}, {"type", "pinned"}},
                                          {{"node", 5}, {"type", "fixed"}}})},
                {"prescribed", json::array({{{"node", 5}, {"ux", move_x}, {"uy", -0.05}}})},
                {"contacts", json::array({{{"node", 6}, {"members", {0}}}})},
                {"analysis", {{"control", {{"type", "load"}, {"steps", steps}}}}}};
  };
  tsm::Model pushed_model;
  const RunResult pushed = run(model_of(5.0, 0.0, 1), pushed_model);
  ASSERT_EQ(pushed.status, tsm::solver::Status::converged) << pushed.message;
  const tsm::solver::ContactPoint& there = contact_of(pushed.steps.back());
  ASSERT_GT(there.force, 1e4);
  const Eigen::Vector2d tip_there = node_position(pushed_model, pushed.steps.back(), 6);
  for (const int steps : {1, 20}) {
    tsm::Model model;
    const RunResult r = run(model_of(2.0, 3.0, steps), model);
    ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
    for (const StepRecord& s : r.steps) ASSERT_GE(contact_of(s).element, 0) << "step " << s.step << ": the tip left the beam";
    const tsm::solver::ContactPoint& c = contact_of(r.steps.back());
    EXPECT_EQ(c.element, there.element) << steps << " steps";
    EXPECT_NEAR(c.alpha, there.alpha, 1e-9) << steps << " steps";
    EXPECT_NEAR(c.force, there.force, 1e-9 * there.force) << steps << " steps";
    EXPECT_LT((node_position(model, r.steps.back(), 6) - tip_there).norm(), 1e-10) << steps << " steps";
    expect_equilibrium(model, r.steps.back());
  }
}

// ---- The assembled tangent with active contacts ----

/// A cantilever of 6 elements (`element`) and a post clamped at its top whose free bottom, node
/// 100 at (x, 0), is the contact node: all of the contact element's dofs are unknowns.
json post_on_cantilever(const char* element, double x) {
  BeamSpec b;
  b.divisions = 6;
  b.A = 1e3;
  b.element = element;
  json m = beam_model(b);
  m["nodes"].push_back({{"id", 100}, {"x", x}, {"y", 0.0}});
  m["nodes"].push_back({{"id", 11}, {"x", x}, {"y", 0.5}});
  m["members"].push_back({{"from", 11}, {"to", 100}, {"divisions", 2}, {"material", "m"}, {"section", "s"}});
  m["supports"] = json::array({{{"node", 1}, {"type", "fixed"}}, {{"node", 11}, {"type", "fixed"}}});
  m["contacts"] = json::array({{{"node", 100}, {"members", "all"}}});
  return m;
}

/// ∂F/∂D over the free dofs by central differences (h = 1e-7) at D, with these contacts.
Eigen::MatrixXd finite_difference_tangent(tsm::assembly::GlobalSystem& system, const tsm::assembly::DofMap& dofs,
                                          const Eigen::VectorXd& D, const std::vector<double>& rotations,
                                          const std::vector<tsm::contact::ActiveContact>& active) {
  const int n = dofs.free_count();
  Eigen::MatrixXd fd(n, n);
  for (int q = 0; q < n; ++q) {
    Eigen::VectorXd plus = D, minus = D;
    plus[dofs.dof(q)] += 1e-7;
    minus[dofs.dof(q)] -= 1e-7;
    tsm::assembly::Evaluation ep, em;
    system.evaluate(plus, rotations, false, ep, active);
    system.evaluate(minus, rotations, false, em, active);
    for (int r = 0; r < n; ++r) fd(r, q) = (ep.internal_force[dofs.dof(r)] - em.internal_force[dofs.dof(r)]) / 2e-7;
  }
  return fd;
}

TEST(ContactAssembly, TangentWithActiveContactsMatchesFiniteDifferences) {
  for (const char* element : {"euler-bernoulli", "timoshenko"}) {
    const tsm::Model model = tsm::io::read_model(post_on_cantilever(element, 0.45));
    tsm::assembly::DofMap dofs(model);
    tsm::assembly::GlobalSystem system(model, dofs);
    tsm::contact::ContactSet tracker(model);
    std::vector<tsm::contact::ContactState> states = tracker.initial_states();
    // A bent, rotated state with the pusher pressed 0.02 into the beam near α = 0.7.
    Eigen::VectorXd D = Eigen::VectorXd::Zero(model.dof_count());
    for (int k = 0; k < model.node_count(); ++k) {
      const double x = model.nodes[k].position.x();
      D.segment<3>(3 * k) << -0.05 * x * x, 0.3 * x * x, 0.6 * x;
    }
    const int c = model.node_index(100);
    const double x_c = 0.45;
    D.segment<2>(3 * c) << -0.05 * x_c * x_c + 0.01, 0.3 * x_c * x_c + 0.02;
    std::vector<double> rotations(model.elements.size(), 0.0);
    tsm::assembly::Evaluation e;
    system.evaluate(D, rotations, true, e);
    tracker.update(D, e.chord_rotations, e.contacts, states, false);
    ASSERT_TRUE(states[0].active);
    const auto active = tracker.active_contacts(states);
    system.evaluate(D, e.chord_rotations, true, e, active);
    ASSERT_GT(std::abs(e.contacts[0].Y), 1.0);
    // Dense K_ff: block part (mirrored; the contact element's symmetric part is in it, the post
    // node joined to the beam's nodes by a pattern the contact added) plus the sliding term.
    ASSERT_EQ(system.contact_rank_one().size(), 1u);  // the sliding term, kept apart for Woodbury
    const Eigen::MatrixXd K = dense_tangent(dofs, system.tangent(), system.contact_rank_one());
    const Eigen::MatrixXd fd = finite_difference_tangent(system, dofs, D, e.chord_rotations, active);
    EXPECT_LE((K - fd).norm(), 1e-6 * fd.norm()) << element;
    EXPECT_GT((K - K.transpose()).norm(), 1e-8 * K.norm()) << "the sliding term makes it non-symmetric";
  }
}

// ---- A vertex: two contact elements at one node ----

/// post_on_cantilever with the post's free bottom (node 100) pressed onto the
/// beam node at x = 0.5, and a tracker state with both elements at that node in contact.
struct VertexSetUp {
  tsm::Model model;
  Eigen::VectorXd D;
  std::vector<tsm::contact::ContactState> states;
  int ending = -1, starting = -1, node = -1;  // the elements ending and starting at the node
};

VertexSetUp vertex_set_up(const char* element) {
  VertexSetUp v;
  v.model = tsm::io::read_model(post_on_cantilever(element, 0.5));
  for (int k = 0; k < v.model.node_count(); ++k)
    if (v.model.nodes[k].id != 100 && v.model.nodes[k].position == Eigen::Vector2d(0.5, 0.0)) v.node = k;
  for (size_t k = 0; k < v.model.elements.size(); ++k) {
    if (v.model.elements[k].member != 0) continue;
    if (v.model.elements[k].end == v.node) v.ending = static_cast<int>(k);
    if (v.model.elements[k].start == v.node) v.starting = static_cast<int>(k);
  }
  // A bent state (the beam kinks at its nodes: chords of a parabola), the pusher 0.02 into it.
  v.D = Eigen::VectorXd::Zero(v.model.dof_count());
  for (int k = 0; k < v.model.node_count(); ++k) {
    const double x = v.model.nodes[k].position.x();
    v.D.segment<3>(3 * k) << -0.05 * x * x, 0.3 * x * x, 0.6 * x;
  }
  v.D.segment<2>(3 * v.model.node_index(100)) << -0.05 * 0.25, 0.3 * 0.25 + 0.02;
  tsm::contact::ContactSet tracker(v.model);
  v.states = tracker.initial_states();
  tsm::contact::ContactState& s = v.states[0];
  s.active = true;
  s.element = v.ending;
  s.vertex = tsm::contact::Vertex{v.starting, -1, 0.0};
  s.side = -1;  // it came from below (y < 0 at the start would be +1: it pushes up), on both elements
  s.alpha = 1.0;
  return v;
}

TEST(ContactVertex, TheAssembledTangentMatchesFiniteDifferences) {
  for (const char* element : {"euler-bernoulli", "timoshenko"}) {
    VertexSetUp v = vertex_set_up(element);
    ASSERT_GE(v.ending, 0);
    ASSERT_GE(v.starting, 0);
    tsm::assembly::DofMap dofs(v.model);
    tsm::assembly::GlobalSystem system(v.model, dofs);
    tsm::contact::ContactSet tracker(v.model);
    const auto active = tracker.active_contacts(v.states);
    ASSERT_EQ(active.size(), 2u);
    std::vector<double> rotations(v.model.elements.size(), 0.0);
    tsm::assembly::Evaluation e;
    system.evaluate(v.D, rotations, true, e, active);
    ASSERT_EQ(e.contacts.size(), 2u);
    ASSERT_GT(std::abs(e.contacts[0].Y), 1.0);
    ASSERT_GT(std::abs(e.contacts[1].Y), 1.0);
    const Eigen::MatrixXd K = dense_tangent(dofs, system.tangent(), system.contact_rank_one());
    const Eigen::MatrixXd fd = finite_difference_tangent(system, dofs, v.D, e.chord_rotations, active);
    EXPECT_LE((K - fd).norm(), 1e-6 * fd.norm()) << element;
  }
}

TEST(ContactVertex, ASidePullingAtAConvergedIterateLetsGoAndBothPullingRelease) {
  VertexSetUp v = vertex_set_up("timoshenko");
  tsm::contact::ContactSet tracker(v.model);
  tsm::assembly::DofMap dofs(v.model);
  tsm::assembly::GlobalSystem system(v.model, dofs);
  std::vector<double> rotations(v.model.elements.size(), 0.0);
  tsm::assembly::Evaluation e;
  system.evaluate(v.D, rotations, false, e);
  // Compression is −side·Y: with side −1 a positive Y presses, a negative one pulls.
  using E = tsm::contact::ContactEvaluation;
  {
    auto states = v.states;  // both press: nothing changes, even at a converged iterate
    EXPECT_FALSE(tracker.update(v.D, e.chord_rotations, {E{0, false, 1.0, 5.0}, E{0, true, 0.0, 3.0}}, states, true).any());
    ASSERT_TRUE(states[0].vertex);
    EXPECT_EQ(states[0].vertex->element, v.starting);
    // Reported: the compression of the resultant 5 n_ending + 3 n_starting (chord normals).
    const auto normal = [&](int element) {
      const tsm::Element& f = v.model.elements[element];
      const Eigen::Vector2d a = v.model.nodes[f.start].position + v.D.segment<2>(3 * f.start);
      const Eigen::Vector2d b = v.model.nodes[f.end].position + v.D.segment<2>(3 * f.end);
      const Eigen::Vector2d t = (b - a).normalized();
      return Eigen::Vector2d(-t.y(), t.x());
    };
    const double resultant = (5.0 * normal(v.ending) + 3.0 * normal(v.starting)).norm();
    EXPECT_LT(resultant, 7.999);  // the chords meet at an angle (0.1 rad here)
    EXPECT_NEAR(states[0].force, resultant, 1e-12 * resultant);
    EXPECT_EQ(states[0].alpha, 1.0);  // on the element ending at the node, at its end
  }
  {
    auto states = v.states;  // one pulls, but the iterate has not converged: held
    EXPECT_FALSE(tracker.update(v.D, e.chord_rotations, {E{0, false, 1.0, 5.0}, E{0, true, 0.0, -3.0}}, states, false).any());
    ASSERT_TRUE(states[0].vertex);
    EXPECT_EQ(states[0].vertex->element, v.starting);
  }
  {
    auto states = v.states;  // the starting element pulls: the ending one carries on alone, held at the node
    const auto changes = tracker.update(v.D, e.chord_rotations, {E{0, false, 1.0, 5.0}, E{0, true, 0.0, -3.0}}, states, true);
    EXPECT_EQ(changes.released, 1);
    EXPECT_TRUE(states[0].active);
    EXPECT_EQ(states[0].element, v.ending);
    EXPECT_FALSE(states[0].vertex);
    EXPECT_EQ(states[0].step.held_node, v.node);
  }
  {
    auto states = v.states;  // the ending element pulls: the starting one carries on
    tracker.update(v.D, e.chord_rotations, {E{0, false, 1.0, -5.0}, E{0, true, 0.0, 3.0}}, states, true);
    EXPECT_EQ(states[0].element, v.starting);
    EXPECT_EQ(states[0].side, -1);
    EXPECT_FALSE(states[0].vertex);
  }
  {
    auto states = v.states;  // both pull: released
    tracker.update(v.D, e.chord_rotations, {E{0, false, 1.0, -5.0}, E{0, true, 0.0, -3.0}}, states, true);
    EXPECT_FALSE(states[0].active);
    EXPECT_FALSE(states[0].vertex);
  }
}

// ---- Released by a pull: the side it let go on holds for the whole beam ----

TEST(ContactDetection, AlongTheNodesPathOnlyWhereTheNodeItselfCrossedTheElement) {
  // The tracker alone, on a 4-element cantilever (0 … 1 along x) and a contact node that starts
  // 0.02 above it at x = 0.125. (a) An iterate throws the node to (1.5, −0.02), past the free end:
  // it ends within no element's span, but its path crossed element 2's chord from above — contact
  // starts there and is carried along the beam to its free end (held there until a converged
  // iterate lets it go). (b) The node stays put outside the beam (x = −0.25) while the beam turns
  // half a turn about its middle: in element 1's own frame the node passed from one side to the
  // other within its span, but the node never met it — no contact.
  BeamSpec b;
  b.divisions = 4;
  const tsm::Model model = tsm::io::read_model(pusher_model(b, 0.125, 0.02, 0.0, -0.02, 1));
  tsm::contact::ContactSet tracker(model);
  const std::vector<double> straight(model.elements.size(), 0.0);
  const int pusher = model.node_index(100);
  {
    std::vector<tsm::contact::ContactState> states = tracker.initial_states();
    Eigen::VectorXd D = Eigen::VectorXd::Zero(model.dof_count());
    D.segment<2>(3 * pusher) = Eigen::Vector2d(1.5 - 0.125, -0.04);
    const tsm::contact::ContactChanges changes = tracker.update(D, straight, {}, states, false);
    EXPECT_EQ(changes.activated, 1);
    ASSERT_TRUE(states[0].active) << "the node's path crossed the beam";
    EXPECT_EQ(states[0].side, 1);  // from above
    EXPECT_EQ(states[0].element, 3) << "carried on to the free end";
  }
  {
    json m = pusher_model(b, -0.25, 0.02, 0.0, -0.02, 1);
    const tsm::Model outside = tsm::io::read_model(m);
    tsm::contact::ContactSet outside_tracker(outside);
    std::vector<tsm::contact::ContactState> states = outside_tracker.initial_states();
    Eigen::VectorXd D = Eigen::VectorXd::Zero(outside.dof_count());
    for (int k = 0; k < outside.node_count(); ++k) {
      if (k == outside.node_index(100)) continue;
      const Eigen::Vector2d x = outside.nodes[k].position, turned = Eigen::Vector2d(1.0 - x.x(), -x.y());
      D.segment<3>(3 * k) << turned - x, std::numbers::pi;
    }
    const std::vector<double> half_turn(outside.elements.size(), std::numbers::pi);
    EXPECT_FALSE(outside_tracker.update(D, half_turn, {}, states, false).any());
    EXPECT_FALSE(states[0].active);
  }
}

TEST(ContactRelease, ANodeThatLetGoByPullingMayNotBeThroughTheBeamAnywhere) {
  // A contact on element 3 of a 10-element cantilever, from above, lets go by pulling at an
  // iterate that has thrown the node far beyond the beam (a diverging Newton iterate): no
  // element's span held it then. If a later converged iterate has it within some element's span
  // on the beam's other side, it went through: passed_through() must say so (before, only the
  // elements that held it at the release were checked, and a beam-on-beam run accepted a state
  // with the tip through the beam). Above the beam, or off its free end, it is fine.
  BeamSpec b;
  b.divisions = 10;
  const tsm::Model model = tsm::io::read_model(pusher_model(b, 0.35, 0.01, 0.0, -0.02, 1));
  tsm::contact::ContactSet tracker(model);
  std::vector<tsm::contact::ContactState> states = tracker.initial_states();
  states[0].active = true;
  states[0].element = 3;
  states[0].side = 1;
  const std::vector<double> rotations(model.elements.size(), 0.0);
  const int pusher = model.node_index(100);
  const auto at = [&](double x, double y) {  // the pusher moved to (x, y), the beam straight
    Eigen::VectorXd D = Eigen::VectorXd::Zero(model.dof_count());
    D.segment<2>(3 * pusher) = Eigen::Vector2d(x - 0.35, y - 0.01);
    return D;
  };
  const Eigen::VectorXd wild = at(5.0, 3.0);
  // Y > 0 on side +1 is a pull (compression −side·Y); the iterate has converged.
  const tsm::contact::ContactChanges changes =
      tracker.update(wild, rotations, {tsm::contact::ContactEvaluation{0, false, 0.4, 10.0}}, states, true);
  ASSERT_EQ(changes.released, 1);
  ASSERT_FALSE(states[0].active);
  EXPECT_TRUE(tracker.passed_through(at(0.75, -0.001), rotations, states));   // under element 7
  EXPECT_TRUE(tracker.passed_through(at(0.05, -0.2), rotations, states));     // under element 0
  EXPECT_FALSE(tracker.passed_through(at(0.75, 0.001), rotations, states));   // above
  EXPECT_FALSE(tracker.passed_through(at(1.2, -0.1), rotations, states));     // beyond the free end
}

TEST(ContactRelease, ANodeThatLetGoOfARingIsThroughItOnlyWhereItIsInside) {
  // A closed ring (radius 1, 120 elements) and a node above its top that lets go by pulling. The
  // side it pressed from, carried round the ring, is the wrong one for the elements at the
  // ring's bottom, whose span the node above the top also lies across: it was called "through"
  // the ring there, and a rope draped over a ring (I = 1e-10) never settled its contacts.
  // Only the element nearest across the node's position counts.
  const json m = {{"materials", {{"steel", {{"E", 2e11}}}}},
                  {"sections", {{"ring", {{"A", 1e-2}, {"I", 1e-4}}}}},
                  {"nodes", json::array({{{"id", 1}, {"x", 0.0}, {"y", -1.0}}, {{"id", 100}, {"x", 0.01}, {"y", 1.01}}})},
                  {"members", json::array({{{"from", 1}, {"to", 1}, {"arc", {{"center", {0.0, 0.0}}, {"sweep", 2.0 * std::numbers::pi}}},
                                            {"divisions", 120}, {"material", "steel"}, {"section", "ring"}}})},
                  {"supports", json::array({{{"node", 1}, {"type", "fixed"}}, {{"node", 100}, {"type", "fixed"}}})},
                  {"contacts", json::array({{{"node", 100}, {"members", {0}}}})},
                  {"analysis", {{"control", {{"type", "load"}, {"steps", 1}}}}}};
  const tsm::Model model = tsm::io::read_model(m);
  tsm::contact::ContactSet tracker(model);
  std::vector<tsm::contact::ContactState> states = tracker.initial_states();
  int top = -1;  // the element under the node
  for (size_t e = 0; e < model.elements.size(); ++e) {
    const Eigen::Vector2d a = model.nodes[model.elements[e].start].position, b = model.nodes[model.elements[e].end].position;
    if (a.y() > 0.9 && b.y() > 0.9 && std::min(a.x(), b.x()) <= 0.01 && std::max(a.x(), b.x()) >= 0.01) top = static_cast<int>(e);
  }
  ASSERT_GE(top, 0);
  const Eigen::Vector2d a = model.nodes[model.elements[top].start].position, b = model.nodes[model.elements[top].end].position;
  const Eigen::Vector2d n(-(b - a).y(), (b - a).x());
  const int side = n.dot(Eigen::Vector2d(0.01, 1.01) - a) > 0.0 ? 1 : -1;  // the node's side of the top element
  states[0].active = true;
  states[0].element = top;
  states[0].side = side;
  const std::vector<double> rotations(model.elements.size(), 0.0);
  const int node = model.node_index(100);
  const auto at = [&](double x, double y) {  // the node moved to (x, y), the ring as drawn
    Eigen::VectorXd D = Eigen::VectorXd::Zero(model.dof_count());
    D.segment<2>(3 * node) = Eigen::Vector2d(x - 0.01, y - 1.01);
    return D;
  };
  const tsm::contact::ContactChanges changes =
      tracker.update(at(0.01, 1.005), rotations, {tsm::contact::ContactEvaluation{0, false, 0.5, side * 10.0}}, states, true);
  ASSERT_EQ(changes.released, 1);
  EXPECT_FALSE(tracker.passed_through(at(0.01, 1.02), rotations, states));   // above the ring
  EXPECT_FALSE(tracker.passed_through(at(0.3, 1.2), rotations, states));     // above, further on
  EXPECT_TRUE(tracker.passed_through(at(0.01, 0.99), rotations, states));    // just inside, under the top
  EXPECT_TRUE(tracker.passed_through(at(0.0, 0.0), rotations, states));      // at the centre
}

}  // namespace
