// Linearised buckling at the unloaded state (solver/buckling, analysis.buckling) against Euler's
// four classical columns, P_cr = π² EI / (K L)² (with the mesh's known excess, (kh)²/12), with
// the cantilever's mode shape 1 − cos(πx/2L);
// a fixed-base portal's sway mode against the slope-deflection equation for it; and the load
// factors of a tension member (none) and of a mechanism (none).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "support/models.hpp"

namespace {

using namespace tsm::test;
using std::numbers::pi;

/// A column along x (L = 4, EI = 1e6, EA 1e4 times stiffer over L²) under P = 1,000 at its top
/// (node 2), its ends held as given, 20 Euler–Bernoulli elements.
json column(const json& supports, int divisions = 20) {
  json m = beam_model({.L = 4.0, .E = 1e6, .G = 4e5, .A = 1e4, .I = 1.0, .shear_area = 1e4, .divisions = divisions});
  m["supports"] = supports;
  m["loads"] = json::array({{{"node", 2}, {"fx", -1000.0}}});
  m["analysis"]["buckling"] = {{"modes", 2}};
  return m;
}

struct EulerCase {
  const char* name;
  json supports;
  double K;  // effective length factor
};

TEST(LinearBuckling, EulersFourColumnsBuckleAtPiSquaredEIOverKLSquared) {
  // Fixed–pinned: K L = π L / 4.4934 (tan x = x).
  const EulerCase cases[] = {
      {"cantilever", json::array({{{"node", 1}, {"type", "fixed"}}}), 2.0},
      {"pinned-pinned", json::array({{{"node", 1}, {"type", "pinned"}}, {{"node", 2}, {"fix", {"uy"}}}}), 1.0},
      {"fixed-pinned", json::array({{{"node", 1}, {"type", "fixed"}}, {{"node", 2}, {"fix", {"uy"}}}}), pi / 4.493409457909064},
      {"fixed-fixed", json::array({{{"node", 1}, {"type", "fixed"}}, {{"node", 2}, {"fix", {"uy", "rz"}}}}), 0.5},
  };
  for (const EulerCase& c : cases) {
    tsm::Model model;
    const auto r = run(column(c.supports), model);
    ASSERT_EQ(r.buckling.modes.size(), 2u) << c.name;
    const double exact = pi * pi * 1e6 / std::pow(c.K * 4.0, 2) / 1000.0;
    // The elements' geometric stiffness is their chord's (FORMULATION §1: the string term, the
    // axial force turning with the chord), which a chain of elements of length h takes for the
    // mode sin(kx) as P (kh/2)² / sin²(kh/2) = P (1 + (kh)²/12 + …), k = π / KL: 20 elements
    // lie 0.05 % (cantilever) to 0.8 % (fixed–fixed) above Euler, each as that says to 1e-4.
    const double kh = pi / (c.K * 4.0) * (4.0 / 20.0);
    EXPECT_NEAR(r.buckling.modes[0].load_factor, exact * (1.0 + kh * kh / 12.0), 1e-4 * exact) << c.name;
    EXPECT_GT(r.buckling.modes[1].load_factor, 2.0 * r.buckling.modes[0].load_factor) << c.name;
  }
}

TEST(LinearBuckling, TheCantileversModeIsOneLessCosine) {
  tsm::Model model;
  const auto r = run(column(json::array({{{"node", 1}, {"type", "fixed"}}})), model);
  ASSERT_FALSE(r.buckling.modes.empty());
  const Eigen::VectorXd& shape = r.buckling.modes[0].shape;
  // Transverse (uy) along the column, 1 at the tip: 1 − cos(π x / 2L), x = node's drawn x.
  for (int k = 0; k < model.node_count(); ++k) {
    const double x = model.nodes[k].position.x();
    EXPECT_NEAR(shape[3 * k + 1], 1.0 - std::cos(pi * x / 8.0), 2e-3) << "x " << x;
    EXPECT_NEAR(shape[3 * k], 0.0, 1e-6) << "x " << x;
  }
}

TEST(LinearBuckling, AFixedBasePortalSwaysAtItsSlopeDeflectionLoad) {
  // Columns h = 3 and a beam b = 4 of equal EI, fixed at the base, P on each column's top. In
  // the sway mode the beam bends in double curvature (6EI/b at each end), each column fixed at
  // its foot and held at its top by that spring: slope-deflection gives the alignment chart's
  // sway equation with G_A = 0, G_B = (EI/h)/(EI/b), x / tan x = −6 / G_B, P_cr = x² EI / h²
  // (the beam's shortening left out: EA is large).
  const double h = 3.0, b = 4.0, EI = 1e6, P = 1000.0;
  const double G = (1.0 / h) / (1.0 / b);
  double lo = pi / 2 + 1e-9, hi = pi - 1e-9;  // x/tan x runs from 0 to −∞ on (π/2, π)
  for (int k = 0; k < 200; ++k) {
    const double x = 0.5 * (lo + hi);
    (x / std::tan(x) > -6.0 / G ? lo : hi) = x;
  }
  const double exact = std::pow(0.5 * (lo + hi), 2) * EI / (h * h) / P;
  json m = {{"materials", {{"m", {{"E", EI}}}}},
            {"sections", {{"s", {{"A", 1e4}, {"I", 1.0}}}}},
            {"nodes", json::array({{{"id", 1}, {"x", 0}, {"y", 0}}, {{"id", 2}, {"x", 0}, {"y", h}},
                                   {{"id", 3}, {"x", b}, {"y", h}}, {{"id", 4}, {"x", b}, {"y", 0}}})},
            {"members", json::array({{{"from", 1}, {"to", 2}, {"material", "m"}, {"section", "s"}, {"divisions", 20}},
                                     {{"from", 2}, {"to", 3}, {"material", "m"}, {"section", "s"}, {"divisions", 20}},
                                     {{"from", 3}, {"to", 4}, {"material", "m"}, {"section", "s"}, {"divisions", 20}}})},
            {"supports", json::array({{{"node", 1}, {"type", "fixed"}}, {{"node", 4}, {"type", "fixed"}}})},
            {"loads", json::array({{{"node", 2}, {"fy", -P}}, {{"node", 3}, {"fy", -P}}})},
            {"analysis", {{"control", {{"type", "load"}, {"steps", 1}}}, {"buckling", {{"modes", 1}}}}}};
  tsm::Model model;
  const auto r = run(m, model);
  ASSERT_EQ(r.buckling.modes.size(), 1u);
  EXPECT_NEAR(r.buckling.modes[0].load_factor, exact, 2e-3 * exact);
  // A sway: both tops move along x alike.
  const Eigen::VectorXd& shape = r.buckling.modes[0].shape;
  EXPECT_NEAR(std::abs(shape[3 * 1]), 1.0, 1e-3);
  EXPECT_NEAR(shape[3 * 1], shape[3 * 2], 1e-3);
  // Two elements a member: the load compresses four elements, so that the geometric stiffness
  // has rank 4, fewer than the subspace's vectors (it lost its other directions after one
  // iteration, and read uninitialised columns once). Three modes, ascending, the first the sway
  // with the coarse mesh's excess.
  for (auto& member : m["members"]) member["divisions"] = 2;
  m["analysis"]["buckling"]["modes"] = 3;
  const auto coarse = run(m, model);
  ASSERT_EQ(coarse.buckling.modes.size(), 3u);
  EXPECT_GT(coarse.buckling.modes[0].load_factor, exact);
  EXPECT_LT(coarse.buckling.modes[0].load_factor, 1.15 * exact);
  EXPECT_LT(coarse.buckling.modes[0].load_factor, coarse.buckling.modes[1].load_factor);
  EXPECT_LT(coarse.buckling.modes[1].load_factor, coarse.buckling.modes[2].load_factor);
}

TEST(LinearBuckling, ItIsWhereThePerfectColumnsPathTurnsUnstable) {
  // The cantilever column under 200 times the load, in 25 load steps past its critical load
  // (λ ≈ 0.77): the path stays straight, and bisection on its tangent's inertia (stability.hpp)
  // finds where it turns indefinite — the linearised estimate's λ, the shortening aside (1e-5).
  json m = column(json::array({{{"node", 1}, {"type", "fixed"}}}));
  m["loads"][0]["fx"] = -2e5;
  m["analysis"]["control"] = {{"type", "load"}, {"steps", 25}};
  tsm::Model model;
  const auto r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  ASSERT_FALSE(r.buckling.modes.empty());
  ASSERT_FALSE(r.critical_points.empty());
  EXPECT_NEAR(r.critical_points[0].load_factor, r.buckling.modes[0].load_factor, 1e-4 * r.buckling.modes[0].load_factor);
}

TEST(LinearBuckling, FromAStateOfTheColumnItIsTheSameEstimate) {
  // The cantilever column's path before buckling is linear (a uniform shortening, 1e-4 of it at
  // most here): estimated from the state at λ₀ = 0.5 or 0.7 (`"at": "end"`), the critical load is
  // the unloaded estimate's, the shortening aside (< 1e-4), and the same mode.
  json m = column(json::array({{{"node", 1}, {"type", "fixed"}}}));
  m["loads"][0]["fx"] = -2e5;  // λ_cr ≈ 0.77
  tsm::Model model;
  const auto unloaded = run(m, model);
  ASSERT_EQ(unloaded.buckling.modes.size(), 2u);
  EXPECT_EQ(unloaded.buckling.step, 0);
  m["analysis"]["buckling"]["at"] = "end";
  for (const double base : {0.5, 0.7}) {
    m["analysis"]["control"] = {{"type", "load"}, {"path", {base}}};
    const auto r = run(m, model);
    ASSERT_EQ(r.buckling.modes.size(), 2u) << base;
    EXPECT_EQ(r.buckling.step, 1);
    EXPECT_EQ(r.buckling.base_load_factor, base);
    for (int k = 0; k < 2; ++k) {
      const double expected = unloaded.buckling.modes[k].load_factor;
      EXPECT_NEAR(r.buckling.modes[k].load_factor, expected, 1e-4 * expected) << base << " mode " << k;
      EXPECT_LT((r.buckling.modes[k].shape - unloaded.buckling.modes[k].shape).cwiseAbs().maxCoeff(), 1e-3);
    }
  }
}

TEST(LinearBuckling, AtAStepItIsThatStatesEstimateWhateverTheOutputKeeps) {
  // `"at": 2` on a path 0.3, 0.6, 0.7 is the estimate `"at": "end"` gives on the path 0.3, 0.6:
  // the step's state is kept for it though the output keeps only the last; a step the run does
  // not reach leaves no modes and a note that says so.
  json m = column(json::array({{{"node", 1}, {"type", "fixed"}}}));
  m["loads"][0]["fx"] = -2e5;
  tsm::Model model;
  m["analysis"]["buckling"]["at"] = "end";
  m["analysis"]["control"] = {{"type", "load"}, {"path", {0.3, 0.6}}};
  const auto end = run(m, model);
  m["analysis"]["buckling"]["at"] = 2;
  m["analysis"]["output"] = "last";
  m["analysis"]["control"] = {{"type", "load"}, {"path", {0.3, 0.6, 0.7}}};
  const auto at = run(m, model);
  ASSERT_EQ(at.buckling.modes.size(), end.buckling.modes.size());
  EXPECT_EQ(at.buckling.step, 2);
  EXPECT_EQ(at.buckling.base_load_factor, 0.6);
  for (size_t k = 0; k < at.buckling.modes.size(); ++k)
    EXPECT_NEAR(at.buckling.modes[k].load_factor, end.buckling.modes[k].load_factor, 1e-12 * end.buckling.modes[k].load_factor);
  EXPECT_TRUE(at.steps[1].has_state) << "kept for the estimate";
  EXPECT_FALSE(at.steps[0].has_state) << "the output keeps the last";
  m["analysis"]["buckling"]["at"] = 9;
  const auto unreached = run(m, model);
  EXPECT_TRUE(unreached.buckling.modes.empty());
  ASSERT_FALSE(unreached.notes.empty());
  EXPECT_NE(unreached.notes.back().find("asked at step 9, which the run did not reach"), std::string::npos) << unreached.notes.back();
}

TEST(LinearBuckling, FromStatesNearerThePathsBifurcationItComesNearerIt) {
  // A fixed-base portal (columns 3 m, beam 4 m in two members, EI = 1e6, EA = 1e8) under P on each
  // column's top and 4P at mid-span: the beam's bending sways nothing but loads the columns with
  // moments, so that the path before the sway is not linear. The path under load control passes
  // the sway bifurcation, which bisection on its tangent's inertia finds; the linearised estimate
  // from the unloaded state is 11 % below it, and from states nearer it nearer it.
  const double h = 3.0, b = 4.0, P = 1000.0;
  json m = {{"materials", {{"m", {{"E", 1e6}}}}},
            {"sections", {{"s", {{"A", 1e2}, {"I", 1.0}}}}},
            {"nodes", json::array({{{"id", 1}, {"x", 0}, {"y", 0}}, {{"id", 2}, {"x", 0}, {"y", h}}, {{"id", 3}, {"x", b}, {"y", h}},
                                   {{"id", 4}, {"x", b}, {"y", 0}}, {{"id", 5}, {"x", b / 2}, {"y", h}}})},
            {"members", json::array({{{"from", 1}, {"to", 2}, {"material", "m"}, {"section", "s"}, {"divisions", 20}},
                                     {{"from", 2}, {"to", 5}, {"material", "m"}, {"section", "s"}, {"divisions", 10}},
                                     {{"from", 5}, {"to", 3}, {"material", "m"}, {"section", "s"}, {"divisions", 10}},
                                     {{"from", 3}, {"to", 4}, {"material", "m"}, {"section", "s"}, {"divisions", 20}}})},
            {"supports", json::array({{{"node", 1}, {"type", "fixed"}}, {{"node", 4}, {"type", "fixed"}}})},
            {"loads", json::array({{{"node", 2}, {"fy", -P}}, {{"node", 3}, {"fy", -P}}, {{"node", 5}, {"fy", -4 * P}}})},
            {"analysis", {{"control", {{"type", "load"}, {"path", {100, 200, 250, 275, 300}}}}, {"buckling", {{"modes", 1}}}}}};
  tsm::Model model;
  const auto path = run(m, model);
  ASSERT_EQ(path.status, tsm::solver::Status::converged) << path.message;
  ASSERT_EQ(path.critical_points.size(), 1u);
  const double bifurcation = path.critical_points[0].load_factor;
  ASSERT_EQ(path.buckling.modes.size(), 1u);
  double error = bifurcation - path.buckling.modes[0].load_factor;
  EXPECT_GT(error, 0.1 * bifurcation) << "the unloaded estimate, well below";
  m["analysis"]["buckling"]["at"] = "end";
  for (const double base : {100.0, 200.0, 250.0, 270.0, 278.0}) {
    m["analysis"]["control"] = {{"type", "load"}, {"path", {base}}};
    const auto r = run(m, model);
    ASSERT_EQ(r.buckling.modes.size(), 1u) << base;
    const double nearer = bifurcation - r.buckling.modes[0].load_factor;
    EXPECT_GT(nearer, 0.0) << base;
    EXPECT_LT(nearer, error) << base;
    error = nearer;
    // A sway: both tops move along x alike.
    const Eigen::VectorXd& shape = r.buckling.modes[0].shape;
    EXPECT_NEAR(shape[3 * 1], shape[3 * 2], 1e-3) << base;
  }
  EXPECT_LT(error, 5e-3 * bifurcation) << "from 278, within 0.5 % of the path's";
}

TEST(LinearBuckling, AModeBelowTheFactorisationsRoundOffIsLeftOutAndSaidSo) {
  // A column 1,000 m long and 0.035 m deep (r = 0.01) in 20,000 elements: its first mode's
  // stiffness, EI (π/L)⁴ h, is 2e-17 of an element's axial EA/h — below double precision's
  // round-off, where the factorisation cannot resolve it (in 10⁵ elements it gave λ = 11 for the
  // exact 1.97, the modes' residuals as large as their terms). A shorter
  // column of the same elements resolves (λ within 1e-6 of π²EI/L²).
  json m = column(json::array({{{"node", 1}, {"type", "pinned"}}, {{"node", 2}, {"fix", {"uy"}}}}), 20000);
  m["materials"]["m"]["E"] = 2e11;
  m["sections"]["s"] = {{"A", 1e-2}, {"I", 1e-6}, {"shear_area", 1e-2}};
  m["nodes"][1]["x"] = 1000.0;
  m["loads"][0]["fx"] = -1.0;
  m["analysis"]["output"] = "last";
  tsm::Model model;
  const auto r = run(m, model);
  EXPECT_TRUE(r.buckling.modes.empty());
  EXPECT_TRUE(r.buckling.unresolved);
  ASSERT_FALSE(r.notes.empty());
  EXPECT_NE(r.notes.back().find("linearised buckling resolved 0 of the 2 modes asked for"), std::string::npos) << r.notes.back();
  m["members"][0]["divisions"] = 200;
  m["nodes"][1]["x"] = 10.0;
  const auto resolved = run(m, model);
  ASSERT_EQ(resolved.buckling.modes.size(), 2u);
  const double exact = pi * pi * 2e11 * 1e-6 / 100.0;
  EXPECT_NEAR(resolved.buckling.modes[0].load_factor, exact * (1.0 + std::pow(pi / 200.0, 2) / 12.0), 1e-6 * exact);
}

TEST(LinearBuckling, ATensionMemberDoesNotBuckle) {
  json m = column(json::array({{{"node", 1}, {"type", "pinned"}}, {{"node", 2}, {"fix", {"uy"}}}}));
  m["loads"][0]["fx"] = 1000.0;
  tsm::Model model;
  EXPECT_TRUE(run(m, model).buckling.modes.empty());
}

TEST(LinearBuckling, TheReaderRefusesWhatTheLinearSolutionLeavesOut) {
  json m = column(json::array({{{"node", 1}, {"type", "pinned"}}, {{"node", 2}, {"fix", {"uy"}}}}));
  m["analysis"]["buckling"] = {{"modes", 0}};
  EXPECT_NE(refusal(m).find("analysis.buckling.modes"), std::string::npos) << refusal(m);
  m["analysis"]["buckling"] = {{"mode", 2}};
  EXPECT_NE(refusal(m).find("analysis.buckling.mode: unknown key \"mode\""), std::string::npos) << refusal(m);
  m["analysis"]["buckling"] = {{"modes", 2}, {"at", "middle"}};
  EXPECT_NE(refusal(m).find("analysis.buckling.at: expected \"unloaded\", \"end\" or a step number, got \"middle\""), std::string::npos)
      << refusal(m);
  m["analysis"]["buckling"]["at"] = 0;
  EXPECT_NE(refusal(m).find("analysis.buckling.at"), std::string::npos) << refusal(m);
  m["analysis"]["buckling"]["at"] = true;
  EXPECT_NE(refusal(m).find("analysis.buckling.at: expected"), std::string::npos) << refusal(m);
  m["analysis"]["buckling"] = {{"modes", 2}};
  m["loads"][0]["follower"] = true;
  EXPECT_NE(refusal(m).find("analysis.buckling: linearised buckling is not available with follower loads"), std::string::npos)
      << refusal(m);
}

}  // namespace
