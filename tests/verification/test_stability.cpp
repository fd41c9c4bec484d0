// The stability of converged states: the number of negative eigenvalues of the tangent there
// (its inertia, from the LDLᵀ factorisation's pivots). A perfect cantilever column compressed
// under load control stays straight and converges past its buckling loads, where the exact
// critical loads (2n − 1)² π² EI / 4L² say how many modes have gone unstable; an imperfect
// column below its Euler load stays stable; Williams' toggle (test_arc_length) is unstable
// exactly between its two limit points; a pin-roller beam closed into a ring is neutral; a
// column of 10⁴ elements, whose pivots round off its bending stiffness, is told unknown.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <sstream>

#include "support/models.hpp"
#include "tsmframe/io/results_writer.hpp"
#include "tsmframe/linalg/inertia.hpp"

namespace {

using namespace tsm::test;
using std::numbers::pi;

class PerfectColumn : public ::testing::TestWithParam<const char*> {};

// Loads of 2, 4, 6, 8 and 10 times the first critical load: one mode lost from 1×, the second
// from 9× (the discrete model's critical loads lie within a few per cent of the exact ones at 20
// elements; the loads stand ≥ 10 % away from them). EA is large: the shortening (≤ 3e-5) moves
// the critical loads by as little.
TEST_P(PerfectColumn, PastItsBucklingLoadsUnderLoadControlItIsToldUnstable) {
  const double L = 2.0, E = 1.0, I = 1.0;
  json m = beam_model({.L = L, .E = E, .G = 0.4, .A = 1e6, .I = I, .shear_area = 1e7, .divisions = 20, .element = GetParam()});
  const double critical = pi * pi * E * I / (4.0 * L * L);
  m["supports"] = json::array({{{"node", 1}, {"type", "fixed"}}});
  m["loads"] = json::array({{{"node", 2}, {"fx", -10.0 * critical}}});
  m["analysis"]["control"] = {{"type", "load"}, {"steps", 5}};
  tsm::Model model;
  const auto r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  ASSERT_EQ(r.steps.size(), 5u);
  const int expected[] = {1, 1, 1, 1, 2};
  for (int k = 0; k < 5; ++k) EXPECT_EQ(r.steps[k].negative_eigenvalues, expected[k]) << "step " << k + 1;
  ASSERT_EQ(r.notes.size(), 1u);
  EXPECT_NE(r.notes[0].find("steps 1–5 end on unstable equilibria under their loads"), std::string::npos) << r.notes[0];
  EXPECT_NE(r.notes[0].find("1 to 2 negative eigenvalues"), std::string::npos) << r.notes[0];
  // No converged step before the first is known stable: no bracket (the start is λ = 0).
  EXPECT_EQ(r.notes[0].find("stable at load factor"), std::string::npos) << r.notes[0];
  EXPECT_TRUE(r.critical_points.empty());
  EXPECT_NE(r.notes[0].find("bifurcation point"), std::string::npos) << r.notes[0];
  EXPECT_NE(r.notes[0].find("imperfection"), std::string::npos) << r.notes[0];
  std::ostringstream json_text;
  tsm::io::write_results_json(json_text, model, r);
  const json written = json::parse(json_text.str());
  EXPECT_EQ(written["steps"][4]["negative_eigenvalues"], 2);
  EXPECT_EQ(written["notes"][0], r.notes[0]);

  // Steps through the critical load (stable at 0.8 of it, unstable at 1.2): bisection on the
  // tangent's inertia between them finds it, λ = 0.1, within the elements' discretisation error
  // (20 elements: 6e-4 above, the chord-based geometric stiffness).
  m["analysis"]["control"]["steps"] = 25;  // λ = 0.04 k: 10 × the critical load at λ = 1
  const auto through = run(m, model);
  ASSERT_EQ(through.status, tsm::solver::Status::converged) << through.message;
  ASSERT_EQ(through.critical_points.size(), 1u) << "stable → unstable once; 1 → 2 negative eigenvalues is no bracket";
  EXPECT_EQ(through.critical_points[0].step, 3);
  EXPECT_NEAR(through.critical_points[0].load_factor, 0.1, 1e-3 * 0.1);
  EXPECT_LE(std::abs(through.critical_points[0].unstable - through.critical_points[0].stable), 1e-6);
  ASSERT_FALSE(through.notes.empty());
  EXPECT_NE(through.notes[0].find("it turns indefinite at load factor 0.100"), std::string::npos) << through.notes[0];
  m["analysis"]["control"]["steps"] = 5;

  // Below the first critical load: stable, and nothing said.
  m["loads"][0]["fx"] = -0.8 * critical;
  const auto below = run(m, model);
  ASSERT_EQ(below.status, tsm::solver::Status::converged) << below.message;
  for (const auto& s : below.steps) EXPECT_EQ(s.negative_eigenvalues, 0) << "step " << s.step;
  EXPECT_TRUE(below.notes.empty());
}

INSTANTIATE_TEST_SUITE_P(BothTheories, PerfectColumn, ::testing::Values("euler-bernoulli", "timoshenko"));

class PinRollerRing : public ::testing::TestWithParam<const char*> {};

// A beam on a pin and a roller bent by equal and opposite end moments M into a circular arc of
// angle θ = ML/EI (exact for any mesh: the paper's Fig. 3). Short of a full circle the supports
// hold it and it is stable. At θ = 2π its ends meet: the pin's reactions and the roller's all act
// through that point, so the ring may turn about it as a rigid body, and the end moments do no
// work on the turn — a neutral equilibrium, its tangent singular. Its eigenvalue count was the
// sign of round-off (told "unstable … past a bifurcation point" in 220 rows of the Fig. 3 study).
TEST_P(PinRollerRing, ClosedIntoACircleItMayTurnAboutThePinAndIsToldNeutral) {
  const double L = 10.0, E = 2e11, I = 8e-6;
  json m = beam_model({.L = L, .E = E, .G = 8e10, .A = 1e-2, .I = I, .shear_area = 8e-3, .divisions = 12, .element = GetParam()});
  const double M = 2.0 * pi * E * I / L;
  m["supports"] = json::array({{{"node", 1}, {"type", "pinned"}}, {{"node", 2}, {"type", "roller-x"}}});
  m["loads"] = json::array({{{"node", 1}, {"mz", -M}}, {{"node", 2}, {"mz", M}}});
  m["analysis"]["control"] = {{"type", "load"}, {"steps", 4}};
  tsm::Model model;
  const auto r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  ASSERT_EQ(r.steps.size(), 4u);
  for (int k = 0; k < 3; ++k) {  // a quarter, a half and three quarters of the circle
    EXPECT_EQ(r.steps[k].negative_eigenvalues, 0) << "step " << k + 1;
    EXPECT_FALSE(r.steps[k].neutral) << "step " << k + 1;
  }
  EXPECT_NEAR(r.steps[3].displacements[3], -L, 1e-6 * L);  // the roller's end on the pin
  EXPECT_TRUE(r.steps[3].neutral);
  EXPECT_EQ(r.steps[3].negative_eigenvalues, -1);
  ASSERT_EQ(r.neutral_steps.size(), 1u);
  const tsm::FreeMotion& motion = r.neutral_steps[0].motion;
  EXPECT_EQ(r.neutral_steps[0].step, 4);
  EXPECT_EQ(motion.kind, tsm::FreeMotion::Kind::rotation);
  EXPECT_LE(motion.pole.norm(), 1e-6 * L) << motion.pole.transpose();  // about the pin
  EXPECT_EQ(motion.part_nodes, 13);
  ASSERT_EQ(r.notes.size(), 1u);
  EXPECT_EQ(r.notes[0].rfind("step 4 ends in neutral equilibrium: there the supports let the part holding node 1 and the 12 "
                             "nodes joined to it rotate about (",
                             0),
            0u)
      << r.notes[0];
  std::ostringstream json_text;
  tsm::io::write_results_json(json_text, model, r);
  const json written = json::parse(json_text.str());
  EXPECT_FALSE(written["steps"][3].contains("negative_eigenvalues"));
  ASSERT_EQ(written["neutral_equilibria"].size(), 1u);
  EXPECT_EQ(written["neutral_equilibria"][0]["motion"], "rotation");
  EXPECT_EQ(written["neutral_equilibria"][0]["node"], 1);
}

INSTANTIATE_TEST_SUITE_P(BothTheories, PinRollerRing, ::testing::Values("euler-bernoulli", "timoshenko"));

// An imperfect pinned column driven to a mid-span deflection of L/50 under displacement control
// rises towards its Euler load and stays on a stable path (the load still rising at every step).
TEST(ImperfectColumnStability, ItsRisingPathIsStable) {
  const int n = 16;
  const double L = 5.0, E = 2e11, I = 1e-5, A = 1e-2, e0 = 1e-3 * L;
  json m = beam_model({.L = L, .E = E, .G = 8e10, .A = A, .I = I, .shear_area = A, .divisions = 1});
  m["nodes"] = json::array();
  m["members"] = json::array();
  for (int k = 0; k <= n; ++k) m["nodes"].push_back({{"id", k + 1}, {"x", L * k / n}, {"y", e0 * std::sin(pi * k / n)}});
  for (int k = 0; k < n; ++k)
    m["members"].push_back({{"from", k + 1}, {"to", k + 2}, {"material", "m"}, {"section", "s"}});
  m["supports"] = json::array({{{"node", 1}, {"type", "pinned"}}, {{"node", n + 1}, {"type", "roller-x"}}});
  m["loads"] = json::array({{{"node", n + 1}, {"fx", -pi * pi * E * I / (L * L)}}});
  m["analysis"]["control"] = {{"type", "displacement"}, {"node", n / 2 + 1}, {"dof", "uy"}, {"target", 0.02 * L}, {"steps", 8}};
  tsm::Model model;
  const auto r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  for (const auto& s : r.steps) EXPECT_EQ(s.negative_eigenvalues, 0) << "step " << s.step;
  EXPECT_TRUE(r.notes.empty());
}

// ---- A snap-through under load control (the von Mises truss) ----
// Two pin-jointed bars from (∓a, 0) to the apex (0, h), EA, the apex loaded down by P. The bars'
// law is the elements' axial one, N = EA (l − l0)/l0 with exact compatibility, so the truss is
// exact: P(w) = 2 EA (l0 − l)/l0 · (h − w)/l, l = √(a² + (h − w)²) at an apex deflection w. P
// rises to a maximum, falls through zero at w = h and rises again on the inverted side.
struct VonMises {
  double a = 1.0, h = 0.1, EA = 1e6;
  double load(double w) const {
    const double l0 = std::hypot(a, h), l = std::hypot(a, h - w);
    return 2.0 * EA * (l0 - l) / l0 * (h - w) / l;
  }
  double maximum() const {  // dP/dw = 0 before w = h: by trisection
    double lo = 0.0, hi = h;
    for (int k = 0; k < 200; ++k) {
      const double m1 = lo + (hi - lo) / 3.0, m2 = hi - (hi - lo) / 3.0;
      if (load(m1) < load(m2)) lo = m1;
      else hi = m2;
    }
    return load(0.5 * (lo + hi));
  }
  double inverted(double P) const {  // the equilibrium beyond w = 2h (P rising there)
    double lo = 2.0 * h, hi = 100.0 * h;
    for (int k = 0; k < 200; ++k) {
      const double mid = 0.5 * (lo + hi);
      if (load(mid) < P) lo = mid;
      else hi = mid;
    }
    return 0.5 * (lo + hi);
  }
  json model(double P, int steps) const {
    return {{"materials", {{"s", {{"E", EA / 1e-3}}}}},
            {"sections", {{"x", {{"A", 1e-3}, {"I", 1e-9}}}}},
            {"nodes", json::array({{{"id", 1}, {"x", -a}, {"y", 0.0}}, {{"id", 2}, {"x", a}, {"y", 0.0}},
                                   {{"id", 3}, {"x", 0.0}, {"y", h}}})},
            {"members", json::array({{{"from", 1}, {"to", 3}, {"material", "s"}, {"section", "x"}, {"release", "both"}},
                                     {{"from", 3}, {"to", 2}, {"material", "s"}, {"section", "x"}, {"release", "both"}}})},
            {"supports", json::array({{{"node", 1}, {"type", "pinned"}}, {{"node", 2}, {"type", "pinned"}}})},
            {"loads", json::array({{{"node", 3}, {"fy", -P}}})},
            {"analysis", {{"control", {{"type", "load"}, {"steps", steps}}}}}};
  }
};

TEST(SnapThrough, LoadControlPastTheVonMisesTrussMaximumLandsOnTheInvertedEquilibriumAndSaysSo) {
  // 1.5 × the maximum in 10 steps: step 7 (1.05 ×) has no equilibrium nearby and Newton lands on
  // the inverted one, 0.19 further down (24 × the step before per unit load, 101 × the step
  // after). Found as a user loading a shallow arch so, which said nothing of the jump. The path
  // ends where the exact truss does, to rounding.
  const VonMises truss;
  const double P = 1.5 * truss.maximum();
  tsm::Model model;
  const auto r = run(truss.model(P, 10), model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  const int apex = model.node_index(3);
  EXPECT_NEAR(-r.steps.back().displacements[3 * apex + 1], truss.inverted(P), 1e-12);
  int noted = 0;
  for (const std::string& note : r.notes)
    if (note.find("snapped through") != std::string::npos) {
      ++noted;
      EXPECT_EQ(note.rfind("step 7 moved ", 0), 0u) << note;
    }
  EXPECT_EQ(noted, 1);
  // Up to 0.95 × the maximum (a steepening path, no jump): no such note.
  const auto below = run(truss.model(0.95 * truss.maximum(), 10), model);
  ASSERT_EQ(below.status, tsm::solver::Status::converged) << below.message;
  for (const std::string& note : below.notes) EXPECT_EQ(note.find("snapped through"), std::string::npos) << note;
}

}  // namespace

namespace {

// A steel cantilever column 4 m long (100 mm square) compressed past its Euler load
// P = π²EI/4L² in `divisions` elements. Its bending stiffness as a whole against one element's
// transverse stiffness is about h³/8L³ (h the element's length): 1.25e-10 in 10³ elements,
// 1.25e-13 in 10⁴ — below the pivots' rounding there (~1.5e-13 of the diagonal), where the counts
// came out at random (1 negative eigenvalue at 0.95 P, 0 at 0.98 P).
tsm::solver::RunResult long_column(int divisions, tsm::Model& model) {
  const double L = 4.0, E = 2.05e11, I = 1e-4 / 12.0;
  json m = beam_model({.L = L, .E = E, .G = 7.9e10, .A = 0.01, .I = I, .shear_area = 0.01 / 1.2, .divisions = divisions});
  m["supports"] = json::array({{{"node", 1}, {"type", "fixed"}}});
  m["loads"] = json::array({{{"node", 2}, {"fx", -pi * pi * E * I / (4.0 * L * L)}}});
  m["analysis"]["control"] = {{"type", "load"}, {"path", {0.5, 0.9, 0.98, 1.02, 1.1}}};
  return run(m, model);
}

TEST(LongColumn, InAThousandElementsItIsStableBelowEulersLoadAndUnstableAbove) {
  tsm::Model model;
  const auto r = long_column(1000, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  const int expected[] = {0, 0, 0, 1, 1};
  for (int k = 0; k < 5; ++k) EXPECT_EQ(r.steps[k].negative_eigenvalues, expected[k]) << "step " << k + 1;
  EXPECT_TRUE(r.rounded_steps.empty());
  // The bisection narrows onto Euler's load (the mesh's excess (πh/2L)²/12 and the shortening
  // P/EA move it by < 2e-4) until round-off hides the count, within 5e-4 of it (the pivot there
  // is 2e-9 |1 − λ/λ_cr| of its diagonal): it says so rather than bisect on noise.
  ASSERT_EQ(r.critical_points.size(), 1u);
  const tsm::solver::CriticalPoint& c = r.critical_points[0];
  EXPECT_LT(c.stable, c.unstable);
  EXPECT_LE(c.stable, 1.0 + 2e-4);
  EXPECT_GE(c.unstable, 1.0);
  EXPECT_LT(c.unstable - c.stable, 4e-3);
  EXPECT_TRUE(c.rounded);
}

TEST(LongColumn, InTenThousandElementsItsStabilityIsToldUnknownNotGuessed) {
  tsm::Model model;
  const auto r = long_column(10000, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  ASSERT_EQ(r.steps.size(), 5u);
  for (const tsm::solver::StepRecord& s : r.steps) EXPECT_EQ(s.negative_eigenvalues, -1) << "step " << s.step;
  ASSERT_EQ(r.rounded_steps.size(), 5u);
  for (int k = 0; k < 5; ++k) {
    const tsm::solver::RoundedStep& s = r.rounded_steps[k];
    EXPECT_EQ(s.step, k + 1);
    EXPECT_LT(s.pivot.ratio, tsm::linalg::doubtful_pivot);
    EXPECT_GT(s.pivot.node, 0) << "a free node of the column";
  }
  EXPECT_TRUE(r.critical_points.empty()) << "no bisection on noise";
  const int node = model.nodes[r.rounded_steps[0].pivot.node].id;
  ASSERT_EQ(r.notes.size(), 1u);
  EXPECT_NE(r.notes[0].find("steps 1–5 end with their stability unknown"), std::string::npos) << r.notes[0];
  EXPECT_NE(r.notes[0].find("node " + std::to_string(node) + " "), std::string::npos) << r.notes[0];
  // results.json lists them.
  std::ostringstream os;
  tsm::io::write_results_json(os, model, r);
  const json written = json::parse(os.str());
  ASSERT_EQ(written["rounded_inertia"].size(), 5u);
  EXPECT_EQ(written["rounded_inertia"][0]["node"], node);
  EXPECT_EQ(written["rounded_inertia"][4]["step"], 5);
  EXPECT_FALSE(written["steps"][0].contains("negative_eigenvalues")) << "left out, not guessed";
}

}  // namespace
