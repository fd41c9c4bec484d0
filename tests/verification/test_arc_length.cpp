// Arc-length control (issue 6): the von Mises two-bar truss against its closed form through
// both limit points; arc-length and load control agree where both can go; Lee's frame (limit
// load and snap-back) and DaDeppo & Schmidt's 215° arch against published limit loads; Williams'
// toggle against the exact elastica of the same frame; a contact point that slips off a
// cantilever's free end.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "support/models.hpp"

namespace {

using namespace tsm::test;
using tsm::solver::RunResult;
using tsm::solver::StepRecord;

// ---- Von Mises truss: two bars of EA = 1, half-span b = 1, rise h = 0.1, apex load P ----
// One beam element per bar (I = 1e-9: bending negligible), so each bar is exactly a truss bar
// with N = EA (l − l0)/l0; apex drop w: P(w) = 2 EA (L0 − L)/L0 · (h − w)/L, L = √(b² + (h − w)²).

constexpr double rise = 0.1, reference_load = 1e-3;

double truss_load(double w) {
  const double L0 = std::hypot(1.0, rise), L = std::hypot(1.0, rise - w);
  return 2.0 * (L0 - L) / L0 * (rise - w) / L;
}

json truss_model(const json& control) {
  return json{
      {"materials", {{"m", {{"E", 1.0}}}}},
      {"sections", {{"s", {{"A", 1.0}, {"I", 1e-9}}}}},
      {"nodes", json::array({{{"id", 1}, {"x", 0.0}, {"y", 0.0}}, {{"id", 2}, {"x", 1.0}, {"y", rise}},
                             {{"id", 3}, {"x", 2.0}, {"y", 0.0}}})},
      {"members", json::array({{{"from", 1}, {"to", 2}, {"material", "m"}, {"section", "s"}},
                               {{"from", 2}, {"to", 3}, {"material", "m"}, {"section", "s"}}})},
      {"supports", json::array({{{"node", 1}, {"type", "pinned"}}, {{"node", 3}, {"type", "pinned"}}})},
      {"loads", json::array({{{"node", 2}, {"fy", -reference_load}}})},
      {"analysis", {{"control", control}}},
  };
}

TEST(ArcLength, VonMisesTrussFollowsTheClosedFormThroughBothLimitPoints) {
  tsm::Model model;
  const RunResult r = run(truss_model({{"type", "arc-length"}, {"initial_increment", 0.004}, {"max_increment", 0.004},
                                       {"max_steps", 500}, {"until", {{"node", 2}, {"dof", "uy"}, {"value", -0.25}}}}),
                          model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  // Closed-form limit points by a fine scan: the maximum before the bars are flat (w < h), the
  // minimum after (h < w < 2h).
  double p_max = -1.0, p_min = 1.0;
  for (int k = 0; k <= 200000; ++k) {
    const double w = 2.0 * rise * k / 200000.0, p = truss_load(w);
    if (w < rise) p_max = std::max(p_max, p);
    else p_min = std::min(p_min, p);
  }
  for (const StepRecord& s : r.steps) {
    ASSERT_TRUE(s.converged);
    const double w = -node_displacement(model, s, 2)[1];
    EXPECT_NEAR(s.load_factor * reference_load, truss_load(w), 1e-5 * p_max) << "step " << s.step << " w " << w;
  }
  EXPECT_NEAR(-node_displacement(model, r.steps.back(), 2)[1], 0.25, 1e-12);  // landed on `until`
  ASSERT_EQ(r.limit_points.size(), 2u);
  EXPECT_TRUE(r.limit_points[0].maximum);
  EXPECT_FALSE(r.limit_points[1].maximum);
  EXPECT_NEAR(r.limit_points[0].load_factor * reference_load, p_max, 2e-3 * p_max);
  EXPECT_NEAR(r.limit_points[1].load_factor * reference_load, p_min, 2e-3 * std::abs(p_min));
  EXPECT_LT(p_min, 0.0);  // the path dips below zero load and comes back up
}

TEST(ArcLength, AgreesWithLoadControlWhereBothGo) {
  tsm::Model arc_model, load_model;
  const RunResult arc = run(truss_model({{"type", "arc-length"}, {"initial_increment", 0.01}, {"max_steps", 100},
                                         {"until", {{"load_factor", 0.3}}}}),
                            arc_model);
  const RunResult load = run(truss_model({{"type", "load"}, {"steps", 10}}), load_model);
  ASSERT_EQ(arc.status, tsm::solver::Status::converged) << arc.message;
  ASSERT_EQ(load.status, tsm::solver::Status::converged) << load.message;
  EXPECT_EQ(arc.steps.back().load_factor, 0.3);
  // load control to λ = 1 passes 0.3 at step 3
  const StepRecord& at = load.steps[2];
  ASSERT_NEAR(at.load_factor, 0.3, 1e-15);
  const double w_arc = node_displacement(arc_model, arc.steps.back(), 2)[1], w_load = node_displacement(load_model, at, 2)[1];
  EXPECT_NEAR(w_arc, w_load, 1e-8 * std::abs(w_load));  // both converged to tolerance 1e-8
  EXPECT_TRUE(arc.limit_points.empty());
}

// ---- Lee's frame ----
// Column (0,0)–(0,120), beam (0,120)–(120,120), pinned at (0,0) and (120,120), downward load at
// 24 from the knee; E = 720, A = 6, I = 2 (b = 3, h = 2). Limit load P L²/EI ≈ 18.5 (Lee, Manuel &
// Rossow 1968; Schweizerhof & Wriggers, CMAME 59, 1986), followed by a snap-back: the load
// point's deflection turns back along the path.

TEST(ArcLength, TheTrussLimitPointsAreLocatedBetweenCoarseSteps) {
  // Steps of 0.02 (the steps' own extrema 2.5e-3 off): each limit point is located between them
  // to the closed form's extremum, λ to 1e-9 (the equilibria's Newton tolerance is 1e-8), the apex
  // drop there to 1e-3 of the rise (the top is flat: λ − λ* ∝ (w − w*)²). The bars hinged at both
  // ends: with I = 1e-9 their bending alone moves the extremum by 7e-7.
  json m = truss_model({{"type", "arc-length"}, {"initial_increment", 0.02}, {"max_increment", 0.02}, {"max_steps", 500},
                        {"until", {{"node", 2}, {"dof", "uy"}, {"value", -0.25}}}});
  for (json& member : m["members"]) member["release"] = "both";
  tsm::Model model;
  const RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  ASSERT_EQ(r.limit_points.size(), 2u);
  // The closed form's extrema by golden sections: the maximum before the bars are flat, the minimum after.
  const auto extreme = [](double a, double b, double sign) {
    const double g = (std::sqrt(5.0) - 1.0) / 2.0;
    for (int k = 0; k < 200; ++k) {
      const double c = b - g * (b - a), d = a + g * (b - a);
      if (sign * truss_load(c) > sign * truss_load(d)) b = d;
      else a = c;
    }
    return 0.5 * (a + b);
  };
  const double w_max = extreme(0.0, rise, 1.0), w_min = extreme(rise, 2.0 * rise, -1.0);
  const double exact[2][2] = {{w_max, truss_load(w_max)}, {w_min, truss_load(w_min)}};
  for (int k = 0; k < 2; ++k) {
    const tsm::solver::LimitPoint& p = r.limit_points[k];
    ASSERT_TRUE(p.refined.has_value()) << "limit point " << k;
    EXPECT_EQ(p.maximum, k == 0);
    EXPECT_FALSE(p.contact_kink);
    const double step_error = std::abs(p.load_factor * reference_load - exact[k][1]);
    EXPECT_GT(step_error, 1e-4 * std::abs(exact[k][1])) << "the steps already hit it: no test of the location";
    EXPECT_NEAR(p.refined->load_factor * reference_load, exact[k][1], 1e-9 * std::abs(exact[k][1])) << "limit point " << k;
    EXPECT_EQ(p.refined->dof, 3 * model.node_index(2) + tsm::uy);
    EXPECT_NEAR(-p.refined->value, exact[k][0], 1e-3 * rise) << "limit point " << k;
    EXPECT_LE(p.refined->evaluations, 6);
    std::printf("[figure] truss limit %d: steps %.3e off, located %.3e off (%d equilibria)\n", k,
                step_error / std::abs(exact[k][1]),
                std::abs(p.refined->load_factor * reference_load - exact[k][1]) / std::abs(exact[k][1]), p.refined->evaluations);
  }
}

TEST(ArcLength, LeesFrameLimitLoadAndSnapBack) {
  const json m = {
      {"materials", {{"m", {{"E", 720.0}}}}},
      {"sections", {{"s", {{"A", 6.0}, {"I", 2.0}}}}},
      {"nodes", json::array({{{"id", 1}, {"x", 0}, {"y", 0}}, {{"id", 2}, {"x", 0}, {"y", 120}},
                             {{"id", 3}, {"x", 24}, {"y", 120}}, {{"id", 4}, {"x", 120}, {"y", 120}}})},
      {"members", json::array({{{"from", 1}, {"to", 2}, {"divisions", 20}, {"material", "m"}, {"section", "s"}},
                               {{"from", 2}, {"to", 3}, {"divisions", 4}, {"material", "m"}, {"section", "s"}},
                               {{"from", 3}, {"to", 4}, {"divisions", 16}, {"material", "m"}, {"section", "s"}}})},
      {"supports", json::array({{{"node", 1}, {"type", "pinned"}}, {{"node", 4}, {"type", "pinned"}}})},
      {"loads", json::array({{{"node", 3}, {"fy", -1.0}}})},
      {"analysis", {{"control", {{"type", "arc-length"}, {"initial_increment", 1.0}, {"max_increment", 1.0},
                                 {"max_steps", 2000}, {"until", {{"node", 3}, {"dof", "uy"}, {"value", -90.0}}}}},
                    {"output", "all"}}},
  };
  tsm::Model model;
  const RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  ASSERT_FALSE(r.limit_points.empty());
  ASSERT_TRUE(r.limit_points[0].maximum);
  const double normalised = r.limit_points[0].load_factor * 120.0 * 120.0 / (720.0 * 2.0);
  std::printf("[figure] Lee's frame: P L^2/EI at the limit point = %.4f (published 18.5)\n", normalised);
  EXPECT_NEAR(normalised, 18.5, 0.01 * 18.5);
  int reversals = 0;
  for (size_t k = 2; k < r.steps.size(); ++k) {
    const double a = node_displacement(model, r.steps[k - 2], 3)[1], b = node_displacement(model, r.steps[k - 1], 3)[1],
                 c = node_displacement(model, r.steps[k], 3)[1];
    reversals += (b - a) * (c - b) < 0.0;
  }
  EXPECT_GE(reversals, 1) << "no snap-back: the load point's deflection never turned back";
}

// ---- DaDeppo & Schmidt's deep arch ----
// Circular arch, R = 100, 215° (ends 17.5° below the centre's level), clamped at one end and
// hinged at the other, vertical load at the apex, EI = 1e6, EA = 1e8. Limit load P R²/EI = 8.97
// (DaDeppo & Schmidt, J. Appl. Mech. 42, 1975, 894–896), i.e. P = 897.

json deep_arch(const json& control) {
  const double R = 100.0, half = 107.5 * std::numbers::pi / 180.0;
  const double right = std::numbers::pi / 2 - half, left = std::numbers::pi / 2 + half;
  return json{
      {"materials", {{"m", {{"E", 1e6}}}}},
      {"sections", {{"s", {{"A", 100.0}, {"I", 1.0}}}}},
      {"nodes", json::array({{{"id", 1}, {"x", R * std::cos(right)}, {"y", R * std::sin(right)}},
                             {{"id", 2}, {"x", 0.0}, {"y", R}},
                             {{"id", 3}, {"x", R * std::cos(left)}, {"y", R * std::sin(left)}}})},
      {"members", json::array({{{"from", 1}, {"to", 2}, {"divisions", 20}, {"material", "m"}, {"section", "s"},
                                {"arc", {{"center", {0.0, 0.0}}, {"sweep", half}}}},
                               {{"from", 2}, {"to", 3}, {"divisions", 20}, {"material", "m"}, {"section", "s"},
                                {"arc", {{"center", {0.0, 0.0}}, {"sweep", half}}}}})},
      {"supports", json::array({{{"node", 1}, {"type", "fixed"}}, {{"node", 3}, {"type", "pinned"}}})},
      {"loads", json::array({{{"node", 2}, {"fy", -1.0}}})},
      {"analysis", {{"control", control}, {"output", "last"}}},
  };
}

TEST(ArcLength, DeepArchLimitLoad) {
  tsm::Model model;
  const RunResult r = run(deep_arch({{"type", "arc-length"}, {"initial_increment", 1.0}, {"max_increment", 2.0},
                                     {"max_steps", 1000}, {"until", {{"node", 2}, {"dof", "uy"}, {"value", -120.0}}}}),
                          model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  ASSERT_FALSE(r.limit_points.empty());
  ASSERT_TRUE(r.limit_points[0].maximum);
  std::printf("[figure] 215 deg arch: limit load P = %.2f (published 897)\n", r.limit_points[0].load_factor);
  EXPECT_NEAR(r.limit_points[0].load_factor, 897.0, 0.01 * 897.0);
}

TEST(ArcLength, ADeepArchLoadedPastItsMaximumUnderLoadControlIsToldToUseArcLength) {
  // 2,000 in two steps, each past the limit load: cutback converges ever closer below 897, then
  // fails. The arch softens from the first step on, so a converged step's secant stiffness
  // |Δλ|/‖ΔD‖ just below the maximum was still a quarter of the first step's and the run did not
  // say why it stopped; the tangent's (the first iterate's) is 3 % of it. (In one step Newton
  // lands on the arch snapped through, which carries 2,000: an equilibrium, not this path's.)
  tsm::Model model;
  json m = deep_arch({{"type", "load"}, {"steps", 2}});
  m["loads"][0]["fy"] = -2000.0;
  const RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::cutback_limit) << r.message;
  ASSERT_FALSE(r.steps.empty());
  double reached = 0.0;  // the largest converged load, below the maximum
  for (const StepRecord& s : r.steps)
    if (s.converged) reached = std::max(reached, 2000.0 * s.load_factor);
  EXPECT_LT(reached, 897.0 * 1.01);
  EXPECT_GT(reached, 897.0 * 0.95);
  EXPECT_NE(r.message.find("the load seems to have reached a maximum (a limit point"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("use arc-length control"), std::string::npos) << r.message;
}

TEST(ArcLength, TheDeepArchsMaximumIsToldSoBesideFortyContactsInTouch) {
  // The same run with a plank of 40 contact nodes lying on a beam beside the arch, pressed by
  // λ × 1 N/m: past 32 contacts in touch the tangent with their sliding terms goes to the block
  // LU, whose factorisation has no inertia; the step's start factorises the symmetric part for
  // it, so the limit point is still told (without it: "10 cutbacks in a row" and nothing else).
  tsm::Model model;
  json m = deep_arch({{"type", "load"}, {"steps", 2}});
  m["loads"][0]["fy"] = -2000.0;
  const double sixth = 1.0 / 6.0;  // the plank's nodes over the middle of the beam's elements
  for (const json& node : {json{{"id", 11}, {"x", 300.0}, {"y", 0.0}}, json{{"id", 12}, {"x", 340.0}, {"y", 0.0}},
                           json{{"id", 13}, {"x", 300.0 + sixth}, {"y", 0.5}}, json{{"id", 14}, {"x", 339.0 + sixth}, {"y", 0.5}}})
    m["nodes"].push_back(node);
  m["sections"]["ground"] = {{"A", 100.0}, {"I", 1e4}};  // the beam 10⁴ × the plank's EI: no sag to bridge
  m["members"].push_back({{"from", 11}, {"to", 12}, {"divisions", 120}, {"material", "m"}, {"section", "ground"}});
  m["members"].push_back({{"from", 13}, {"to", 14}, {"divisions", 39}, {"material", "m"}, {"section", "s"},
                          {"load", {{"fy", -1.0}}}});
  m["supports"].push_back({{"node", 11}, {"type", "fixed"}});
  m["supports"].push_back({{"node", 12}, {"type", "fixed"}});
  m["supports"].push_back({{"node", 13}, {"fix", {"ux"}}});
  m["contacts"] = json::array({{{"nodes", {{"members", {3}}}}, {"members", {2}}, {"gap", 0.5}}});
  const RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::cutback_limit) << r.message;
  int in_touch = 0;
  for (const auto& c : r.steps.front().contacts) in_touch += c.element >= 0;
  EXPECT_EQ(in_touch, 40);
  EXPECT_NE(r.message.find("the load seems to have reached a maximum (a limit point"), std::string::npos) << r.message;
}

TEST(ArcLength, AnArcLengthFarLongerThanTheStructureIsToldSo) {
  // Δs = 10⁶ on an arch 200 wide: ten cutbacks leave 977, and no arc that long meets the path.
  // The failure names the arc's size against the structure's and what to give instead.
  tsm::Model model;
  const RunResult r = run(deep_arch({{"type", "arc-length"}, {"initial_increment", 1e6}, {"max_increment", 1e6},
                                     {"max_steps", 20}, {"until", {{"node", 2}, {"dof", "uy"}, {"value", -120.0}}}}),
                          model);
  ASSERT_NE(r.status, tsm::solver::Status::converged);
  EXPECT_NE(r.message.find("× the structure's size"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("give initial_increment and max_increment a few per cent of it"), std::string::npos)
      << r.message;
}

TEST(ArcLength, DisplacementControlAcrossTheDeepArchsSnapBackJumpsAndSaysSo) {
  // The crown driven down 150 in 30 steps: past the maximum (897 at a crown drop of ~115) the
  // crown's displacement turns back along the path, so a step lands on another branch and λ
  // leaps to below zero. The run converges — and notes the leap, pointing to arc-length control.
  tsm::Model model;
  const RunResult r =
      run(deep_arch({{"type", "displacement"}, {"node", 2}, {"dof", "uy"}, {"target", -150.0}, {"steps", 30}}), model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  ASSERT_FALSE(r.limit_points.empty());
  EXPECT_NEAR(r.limit_points[0].load_factor, 897.0, 0.02 * 897.0);
  // The leap's note first; then the stability notes (the path past the maximum is unstable under its load).
  ASSERT_GE(r.notes.size(), 1u);
  EXPECT_NE(r.notes[0].find("the path may snap back here"), std::string::npos) << r.notes[0];
  EXPECT_NE(r.notes[0].find("arc-length control follows it"), std::string::npos) << r.notes[0];
  for (size_t k = 1; k < r.notes.size(); ++k)
    EXPECT_NE(r.notes[k].find("unstable equilibri"), std::string::npos) << r.notes[k];
}

TEST(ArcLength, DisplacementControlThroughTheTrussSnapThroughNotesNothing) {
  // The von Mises truss under displacement control: its apex drop is monotonic along the path
  // (a snap-through, no snap-back). In 10 steps λ turns at the minimum and climbs back to zero
  // in one step of the same size as the first: no leap.
  tsm::Model model;
  const RunResult r =
      run(truss_model({{"type", "displacement"}, {"node", 2}, {"dof", "uy"}, {"target", -0.25}, {"steps", 10}}), model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  ASSERT_EQ(r.limit_points.size(), 2u);
  // No leap; only that the steps between the two limit points are unstable under their loads.
  ASSERT_EQ(r.notes.size(), 1u);
  EXPECT_EQ(r.notes[0].find("leapt"), std::string::npos) << r.notes[0];
  EXPECT_NE(r.notes[0].find("unstable equilibri"), std::string::npos) << r.notes[0];
  EXPECT_NE(r.notes[0].find("from the load maximum at step " + std::to_string(r.limit_points[0].step)), std::string::npos)
      << r.notes[0];
}

// ---- Williams' toggle ----
// Two equal aluminium bars, clamped at both supports and rigidly joined at the apex, apex load P
// (Williams, "An approach to the non-linear behaviour of the members of a rigid jointed plane
// framework with finite deflections", Q. J. Mech. Appl. Math. 17, 1964): half-span 12.943,
// rise 0.386, E = 10.3e6, rectangular 0.753 × 0.243 (inches, lb). The reference here is the exact
// solution of the same problem, computed by shooting: by symmetry the apex neither rotates nor
// moves sideways, so one bar is an extensible elastica clamped at both ends, its far end lowered
// by w and carrying P/2 (EI θ' = m, m' = −r' × F, r' = (1 + N/EA) t, N = F·t). Williams' paper
// solved the same continuum problem; its printed limit load could not be checked here, so the test
// compares with an exact solution instead of a quoted number.

struct ToggleElastica {
  static constexpr double E = 10.3e6, b = 0.753, d = 0.243, half_span = 12.943, rise = 0.386;
  static constexpr int rk4_steps = 2000;
  const double EA = E * b * d, EI = E * b * d * d * d / 12.0;
  const double length = std::hypot(half_span, rise), angle = std::atan2(rise, half_span);
  Eigen::Vector3d unknowns = Eigen::Vector3d::Zero();  // (m at the support, F_x, F_y at the apex)

  // (x, y, θ) at the apex for the given unknowns.
  Eigen::Vector3d shoot(const Eigen::Vector3d& u) const {
    const double Fx = u[1], Fy = u[2];
    auto rate = [&](const Eigen::Vector4d& q) {  // q = (x, y, θ, m)
      const double c = std::cos(q[2]), s = std::sin(q[2]), stretch = 1.0 + (Fx * c + Fy * s) / EA;
      return Eigen::Vector4d(stretch * c, stretch * s, q[3] / EI, -stretch * (c * Fy - s * Fx));
    };
    Eigen::Vector4d q(0.0, 0.0, angle, u[0]);
    const double h = length / rk4_steps;
    for (int i = 0; i < rk4_steps; ++i) {
      const Eigen::Vector4d k1 = rate(q), k2 = rate(q + 0.5 * h * k1), k3 = rate(q + 0.5 * h * k2), k4 = rate(q + h * k3);
      q += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    }
    return q.head<3>();
  }

  // Apex load P for an apex drop w (Newton on the three end conditions, warm-started).
  double load(double w) {
    const Eigen::Vector3d target(half_span, rise - w, angle);
    for (int iteration = 0; iteration < 50; ++iteration) {
      const Eigen::Vector3d r = shoot(unknowns) - target;
      if (r.cwiseAbs().maxCoeff() < 1e-12) return -2.0 * unknowns[2];
      Eigen::Matrix3d J;
      for (int j = 0; j < 3; ++j) {
        Eigen::Vector3d du = Eigen::Vector3d::Zero();
        du[j] = 1e-6 * std::max(1.0, std::abs(unknowns[j]));
        J.col(j) = (shoot(unknowns + du) - target - r) / du[j];
      }
      unknowns -= J.partialPivLu().solve(r);
    }
    ADD_FAILURE() << "shooting did not converge at w = " << w;
    return 0.0;
  }

  // Largest (sign = +1) or smallest (sign = −1) load over [lo, hi] by golden-section search.
  double extreme_load(double lo, double hi, double sign) {
    const double g = (std::sqrt(5.0) - 1.0) / 2.0;
    while (hi - lo > 1e-7) {
      const double a = hi - g * (hi - lo), c = lo + g * (hi - lo);
      if (sign * load(a) > sign * load(c)) hi = c;
      else lo = a;
    }
    return load(0.5 * (lo + hi));
  }
};

TEST(ArcLength, WilliamsToggleAgainstTheExactElastica) {
  using T = ToggleElastica;
  const int divisions = 40;  // per bar; the limit load converges as 1/n² (34.15, 33.94, 33.89, 33.875 for 10…80)
  const json m = {
      {"materials", {{"al", {{"E", T::E}}}}},
      {"sections", {{"bar", {{"A", T::b * T::d}, {"I", T::b * T::d * T::d * T::d / 12.0}}}}},
      {"nodes", json::array({{{"id", 1}, {"x", 0.0}, {"y", 0.0}}, {{"id", 2}, {"x", T::half_span}, {"y", T::rise}},
                             {{"id", 3}, {"x", 2.0 * T::half_span}, {"y", 0.0}}})},
      {"members", json::array({{{"from", 1}, {"to", 2}, {"divisions", divisions}, {"material", "al"}, {"section", "bar"}},
                               {{"from", 2}, {"to", 3}, {"divisions", divisions}, {"material", "al"}, {"section", "bar"}}})},
      {"supports", json::array({{{"node", 1}, {"type", "fixed"}}, {{"node", 3}, {"type", "fixed"}}})},
      {"loads", json::array({{{"node", 2}, {"fy", -1.0}}})},
      {"analysis", {{"control", {{"type", "arc-length"}, {"initial_increment", 0.01}, {"max_increment", 0.01},
                                 {"max_steps", 2000}, {"until", {{"node", 2}, {"dof", "uy"}, {"value", -0.5}}}}},
                    {"output", "all"}}},
  };
  tsm::Model model;
  const RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;

  T exact;
  // The path, every 20th step: load against the exact load at the same apex drop; symmetric.
  for (size_t k = 0; k < r.steps.size(); k += 20) {
    const Eigen::Vector3d apex = node_displacement(model, r.steps[k], 2);
    EXPECT_NEAR(r.steps[k].load_factor, exact.load(-apex[1]), 1e-3 * 33.9) << "step " << r.steps[k].step;
    EXPECT_LT(std::abs(apex[0]) + std::abs(apex[2]), 1e-12);
  }
  // Both limit points: the snap-through maximum and the minimum after it.
  ASSERT_EQ(r.limit_points.size(), 2u);
  ASSERT_TRUE(r.limit_points[0].maximum);
  ASSERT_FALSE(r.limit_points[1].maximum);
  exact.load(0.2);  // warm start near the maximum
  const double p_max = exact.extreme_load(0.15, 0.30, +1.0);
  const double p_min = exact.extreme_load(0.32, 0.46, -1.0);
  std::printf("[figure] Williams' toggle: limit loads %.3f / %.3f (exact elastica %.3f / %.3f)\n",
              r.limit_points[0].load_factor, r.limit_points[1].load_factor, p_max, p_min);
  EXPECT_NEAR(r.limit_points[0].load_factor, p_max, 1e-3 * p_max);
  EXPECT_NEAR(r.limit_points[1].load_factor, p_min, 1e-3 * p_min);
  // The tangent's inertia (from the factorisation's pivots, not from λ): one negative eigenvalue
  // strictly between the two limit points, none before the maximum or after the minimum (the
  // limit steps themselves straddle the singular tangent: either).
  for (const auto& s : r.steps) {
    if (s.step == r.limit_points[0].step || s.step == r.limit_points[1].step) continue;
    const bool between = s.step > r.limit_points[0].step && s.step < r.limit_points[1].step;
    EXPECT_EQ(s.negative_eigenvalues, between ? 1 : 0) << "step " << s.step;
  }
}

// ---- A contact point slipping off a cantilever's free end ----

json slip_model(const json& control) {
  BeamSpec b;
  b.divisions = 20;
  b.A = 1e5;
  json m = beam_model(b);
  m["nodes"].push_back({{"id", 100}, {"x", 0.9}, {"y", 0.0}});
  m["supports"] = json::array({{{"node", 1}, {"type", "fixed"}}, {{"node", 100}, {"fix", {"ux", "rz"}}}});
  m["prescribed"] = json::array({{{"node", 100}, {"uy", 1.0}}});
  m["contacts"] = json::array({{{"node", 100}, {"members", "all"}}});
  m["analysis"] = {{"control", control}};
  return m;
}

TEST(ArcLength, ContactSlipsOffTheFreeEndAndThePathGoesOn) {
  tsm::Model model;
  const RunResult r = run(slip_model({{"type", "arc-length"}, {"initial_increment", 0.02}, {"max_increment", 0.02},
                                      {"max_steps", 400}, {"until", {{"load_factor", 1.0}}}}),
                          model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  // The contact force rises while the point slides out to the tip, then the node slips off.
  double largest = 0.0;
  int last_in_contact = -1;
  for (size_t k = 0; k < r.steps.size(); ++k) {
    const auto& c = r.steps[k].contacts.at(0);
    if (c.element < 0) continue;
    largest = std::max(largest, c.force);
    last_in_contact = static_cast<int>(k);
  }
  ASSERT_GE(last_in_contact, 0);
  const auto& final_contact = r.steps[last_in_contact].contacts[0];
  EXPECT_EQ(final_contact.element, 19);        // the last element …
  EXPECT_GT(final_contact.alpha, 0.99);        // … at its free end
  EXPECT_EQ(final_contact.force, largest);     // the load maximum is where it slips off
  EXPECT_LT(last_in_contact + 1, static_cast<int>(r.steps.size()));
  const StepRecord& end = r.steps.back();
  EXPECT_EQ(end.load_factor, 1.0);
  EXPECT_LT(end.contacts[0].element, 0);
  EXPECT_LT(node_displacement(model, end, 2).norm(), 1e-9);  // the beam is straight again
}

TEST(ArcLength, ContactAgreesWithLoadControl) {
  tsm::Model arc_model, load_model;
  const RunResult arc = run(slip_model({{"type", "arc-length"}, {"initial_increment", 0.02}, {"max_steps", 200},
                                        {"until", {{"load_factor", 0.2}}}}),
                            arc_model);
  const RunResult load = run(slip_model({{"type", "load"}, {"steps", 5}}), load_model);
  ASSERT_EQ(arc.status, tsm::solver::Status::converged) << arc.message;
  ASSERT_EQ(load.status, tsm::solver::Status::converged) << load.message;
  const auto hit = std::find_if(load.steps.begin(), load.steps.end(), [](const StepRecord& s) { return s.load_factor == 0.2; });
  ASSERT_NE(hit, load.steps.end());  // λ = 0.2 is a grid point (cutback sub-steps end on the grid)
  const StepRecord& at = *hit;
  EXPECT_EQ(arc.steps.back().contacts[0].element, at.contacts[0].element);
  EXPECT_NEAR(arc.steps.back().contacts[0].alpha, at.contacts[0].alpha, 1e-9);
  EXPECT_NEAR(arc.steps.back().contacts[0].force, at.contacts[0].force, 1e-8 * at.contacts[0].force);
}

}  // namespace

namespace {

// ---- A limit point where a contact point changes elements ----

TEST(ArcLength, AnExtremumWhereAContactChangesElementsIsToldAsSuch) {
  // examples/cantilever-on-cantilever-arc-length.json: one cantilever's tip slides along the other
  // (20 elements), under arc-length control. Each limit point is marked where, and only where, a
  // contact's element changes between the steps around it, and then has a note; with contacts the
  // points are not located (a trial equilibrium would move the contacts' references).
  std::ifstream file(std::string(TSMFRAME_SOURCE_DIR) + "/examples/cantilever-on-cantilever-arc-length.json");
  tsm::Model model;
  const RunResult r = run(json::parse(file), model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  std::vector<const StepRecord*> path;
  for (const StepRecord& s : r.steps)
    if (s.converged) path.push_back(&s);
  int kinks = 0;
  for (const tsm::solver::LimitPoint& p : r.limit_points) {
    EXPECT_FALSE(p.refined.has_value());
    const auto at = std::find_if(path.begin(), path.end(), [&](const StepRecord* s) { return s->step == p.step; });
    ASSERT_TRUE(at != path.end() && at != path.begin() && at + 1 != path.end());
    const auto element = [](const StepRecord* s) { return std::make_pair(s->contacts[0].element, s->contacts[0].partner); };
    const bool changes = element(*(at - 1)) != element(*at) || element(*at) != element(*(at + 1));
    EXPECT_EQ(p.contact_kink, changes) << "step " << p.step;
    kinks += changes;
    const std::string note = "the load " + std::string(p.maximum ? "maximum" : "minimum") + " at step " + std::to_string(p.step);
    EXPECT_EQ(std::count_if(r.notes.begin(), r.notes.end(), [&](const std::string& n) { return n.rfind(note, 0) == 0; }),
              changes ? 1 : 0) << "step " << p.step;
  }
  EXPECT_GE(kinks, 1);
}

}  // namespace
