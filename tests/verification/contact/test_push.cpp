// A cantilever pushed by a rigid point (issue 3): against the linear formula 3EIh/a³ (and its
// Timoshenko counterpart) for a small push, with a gap, and against an exact elastica-with-contact
// solution computed here by shooting for a large one, where the point slides along the beam.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "support/contact_models.hpp"
#include "support/rk4.hpp"

namespace {

using namespace tsm::test;
using tsm::solver::RunResult;
using tsm::solver::StepRecord;

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

// ---- A tip-loaded cantilever resting on rigid points: the contact forces' normal ----
// Inextensible cantilever (EI = 1, L = 1) under a tip load P down, resting on points fixed at
// (a_k, h_k) below it, a_1 < a_2 < …; each contact force R_k is normal to the beam there.
// Shooting on (R_k, θ_k, x_tip): EI θ' = M(s) = −P (x_tip − x) + Σ over the points not yet passed
// ((a_k − x) Fy_k − (h_k − y) Fx_k), F_k = R_k (−sin θ_k, cos θ_k); at x = a_k, y = h_k and θ = θ_k;
// at s = 1, x = x_tip.
/// The shooting residuals (y − h_k and θ − θ_k at x = a_k, then x(1) − x_tip) for tip load P;
/// u = (R_1 … R_n, θ_1 … θ_n, x_tip).
Eigen::VectorXd resting_cantilever_residual(double P, const std::vector<Eigen::Vector2d>& points, const Eigen::VectorXd& u) {
  const int count = static_cast<int>(points.size());
  const double x_tip = u[2 * count];
  int passed = 0;
  auto f = [&](const std::array<double, 3>& q) {
    double M = -P * (x_tip - q[0]);
    for (int k = passed; k < count; ++k) {
      const double Fx = -u[k] * std::sin(u[count + k]), Fy = u[k] * std::cos(u[count + k]);
      M += (points[k].x() - q[0]) * Fy - (points[k].y() - q[1]) * Fx;
    }
    return std::array<double, 3>{std::cos(q[2]), std::sin(q[2]), M};
  };
  const int n = 4000;
  const double ds = 1.0 / n;
  std::array<double, 3> q = {0.0, 0.0, 0.0};
  Eigen::VectorXd r = Eigen::VectorXd::Ones(2 * count + 1);
  for (int step = 0; step < n; ++step) {
    double left = ds;  // of this step
    std::array<double, 3> next = rk4_step(f, q, left);
    while (passed < count && next[0] >= points[passed].x()) {  // a point within the step: land on it, go on
      const double a = points[passed].x();
      double lo = 0.0, hi = left;
      for (int it = 0; it < 60; ++it) {
        const double mid = 0.5 * (lo + hi);
        (rk4_step(f, q, mid)[0] < a ? lo : hi) = mid;
      }
      q = rk4_step(f, q, 0.5 * (lo + hi));
      left -= 0.5 * (lo + hi);
      r[passed] = q[1] - points[passed].y();
      r[count + passed] = q[2] - u[count + passed];
      ++passed;
      next = rk4_step(f, q, left);
    }
    q = next;
  }
  r[2 * count] = q[0] - x_tip;
  return r;
}

/// The contact forces R_k: damped Newton on (R_k, θ_k, x_tip), the tip load raised from P = 0.5
/// to P in steps of 0.5 (every point held two-sided on the way: a force may pass through zero).
Eigen::VectorXd resting_cantilever_forces(double P, const std::vector<Eigen::Vector2d>& points) {
  const int count = static_cast<int>(points.size());
  Eigen::VectorXd u(2 * count + 1);
  u << Eigen::VectorXd::Constant(count, 0.05 / count), Eigen::VectorXd::Constant(count, -0.15), 1.0;
  for (double load = 0.5; load <= P + 1e-12; load += 0.5)
    for (int it = 0; it < 60; ++it) {
      const Eigen::VectorXd r = resting_cantilever_residual(load, points, u);
      if (r.norm() < 1e-11) break;
      Eigen::MatrixXd J(r.size(), u.size());
      for (int c = 0; c < u.size(); ++c) {
        Eigen::VectorXd v = u;
        const double step = 1e-7 * std::max(1.0, std::abs(u[c]));
        v[c] += step;
        J.col(c) = (resting_cantilever_residual(load, points, v) - r) / step;
      }
      const Eigen::VectorXd du = J.colPivHouseholderQr().solve(r);
      double damping = 1.0;
      while (damping > 1e-3 && resting_cantilever_residual(load, points, u - damping * du).norm() >= r.norm()) damping *= 0.5;
      u -= damping * du;
    }
  return u.head(count);
}

/// The cantilever of `divisions` Euler–Bernoulli elements resting on rigid points, `normal` for each.
json resting_cantilever(int divisions, double P, const std::vector<Eigen::Vector2d>& points, const char* normal) {
  BeamSpec b;
  b.divisions = divisions;
  b.A = 1e7;  // inextensible
  json m = beam_model(b);
  m["supports"] = json::array({{{"node", 1}, {"type", "fixed"}}});
  m["contacts"] = json::array();
  for (size_t k = 0; k < points.size(); ++k) {
    const int id = 100 + static_cast<int>(k);
    m["nodes"].push_back({{"id", id}, {"x", points[k].x()}, {"y", points[k].y()}});
    m["supports"].push_back({{"node", id}, {"type", "fixed"}});
    m["contacts"].push_back({{"node", id}, {"members", "all"}, {"normal", normal}});
  }
  m["loads"] = json::array({{{"node", 2}, {"fy", -P}}});
  m["analysis"] = {{"control", {{"type", "load"}, {"steps", 20}}}, {"cutback", true}};
  return m;
}

TEST(RestingCantileverNormal, TheForceAlongTheBentBeamsNormalConvergesAsHSquared) {
  // The case: a cantilever with a tip load P L²/EI = 10 resting on a rigid point at
  // (0.5, −0.05) L, meshed with 10 … 80 Euler–Bernoulli elements: the contact force against the
  // exact elastica's with the force along the chord's normal (the paper's) and along the bent
  // beam's ("normal": "deflected", issue 27 part 2).
  const double P = 10.0;
  const std::vector<Eigen::Vector2d> point = {{0.5, -0.05}};
  const double exact = resting_cantilever_forces(P, point)[0];
  std::array<std::array<double, 4>, 2> error{};
  const int meshes[4] = {10, 20, 40, 80};
  for (int normal = 0; normal < 2; ++normal)
    for (int q = 0; q < 4; ++q) {
      tsm::Model model;
      const RunResult r = run(resting_cantilever(meshes[q], P, point, normal == 0 ? "chord" : "deflected"), model);
      ASSERT_EQ(r.status, tsm::solver::Status::converged) << meshes[q] << ": " << r.message;
      error[normal][q] = contact_of(r.steps.back()).force / exact - 1.0;
      std::printf("[figure] %d elements, %s normal: contact force %.8g, exact %.8g, error %+.3e\n", meshes[q],
                  normal == 0 ? "chord" : "deflected", contact_of(r.steps.back()).force, exact, error[normal][q]);
    }
  EXPECT_NEAR(exact, 18.4851216, 1e-6);  // the shooting's own check: RK4 with 4,000 steps against 20,000
  for (int q = 0; q < 4; ++q) {
    const double h2 = (10.0 / meshes[q]) * (10.0 / meshes[q]);
    EXPECT_LT(std::abs(error[1][q]), 2e-4 * h2) << "deflected, " << meshes[q];  // within 2·10⁻⁴ (h / 0.1)²
    EXPECT_GT(std::abs(error[0][q]), 1e-3) << "chord, " << meshes[q];            // the paper's stays off
  }
  EXPECT_GT(error[0][1], 0.015);  // the 1.8 % at 20 elements
}

TEST(RestingCantileverNormal, TwoPointsOnOneElementPushAlongTheBentBeamsNormalToo) {
  // The same cantilever resting on two rigid points 0.06 apart: both on one element with 10
  // elements (the k-point element, k = 2), each on its own with 20 … 80. Each contact force
  // against the exact elastica's falls as h² along the bent beam's normal through the change.
  const double P = 10.0;
  const std::vector<Eigen::Vector2d> points = {{0.42, -0.025}, {0.48, -0.055}};
  const Eigen::VectorXd exact = resting_cantilever_forces(P, points);
  ASSERT_GT(exact.minCoeff(), 0.5 * exact.maxCoeff()) << "both points carry the beam: " << exact.transpose();
  std::array<std::array<double, 4>, 2> error{};
  const int meshes[4] = {10, 20, 40, 80};
  for (int normal = 0; normal < 2; ++normal)
    for (int q = 0; q < 4; ++q) {
      tsm::Model model;
      const RunResult r = run(resting_cantilever(meshes[q], P, points, normal == 0 ? "chord" : "deflected"), model);
      ASSERT_EQ(r.status, tsm::solver::Status::converged) << meshes[q] << ": " << r.message;
      const auto& contacts = r.steps.back().contacts;
      ASSERT_EQ(contacts.size(), 2u);
      EXPECT_EQ(contacts[0].element == contacts[1].element, meshes[q] == 10) << "both points on one element";
      for (int k = 0; k < 2; ++k) error[normal][q] = std::max(error[normal][q], std::abs(contacts[k].force / exact[k] - 1.0));
      std::printf("[figure] %d elements, %s normal: forces %.8g %.8g, exact %.8g %.8g, worst error %.3e\n", meshes[q],
                  normal == 0 ? "chord" : "deflected", contacts[0].force, contacts[1].force, exact[0], exact[1],
                  error[normal][q]);
    }
  for (int q = 0; q < 4; ++q) {
    const double h2 = (10.0 / meshes[q]) * (10.0 / meshes[q]);
    EXPECT_LT(error[1][q], 1.5e-2 * h2) << "deflected, " << meshes[q];  // within 1.5 % (h / 0.1)²
    if (q > 0) EXPECT_NEAR(error[1][q - 1] / error[1][q], 4.0, 0.6) << "deflected, " << meshes[q];  // h²
  }
  EXPECT_GT(error[0][0], 2.0 * error[1][0]);  // the k-point element along the chord's normal is off more
  EXPECT_GT(error[0][3], 10.0 * error[1][3]);
}

TEST(RestingCantileverNormal, TwoPointsOnOneElementOfAFiveElementCantileverSettle) {
  // The same two points on a cantilever of five elements (one element, 0.2 long, carries both,
  // 0.3 of it apart). When the second point touched, its contact pulled, let go, and the node
  // was found through the beam again, forever ("contacts keep switching on and off" at
  // λ = 0.748, along the bent beam's normal): detection measured the gap from the element's free
  // shape, not from the shape the first point's force gives it. At a converged iterate it now
  // measures from the loaded shape (ElementLoads, ContactGeometry::loaded_deflection), so the
  // run settles on a state both tests agree on: every point in touch pushes, and every node out
  // of touch is clear of the loaded beam (the converged state is accepted only so). So coarse a
  // mesh is not accurate (the exact elastica has both points pushing): docs/contact-normal.md.
  const double P = 10.0;
  const std::vector<Eigen::Vector2d> points = {{0.42, -0.025}, {0.48, -0.055}};
  const Eigen::VectorXd exact = resting_cantilever_forces(P, points);
  for (const char* normal : {"deflected", "chord"}) {
    tsm::Model model;
    const RunResult r = run(resting_cantilever(5, P, points, normal), model);
    ASSERT_EQ(r.status, tsm::solver::Status::converged) << normal << ": " << r.message;
    double total = 0.0;
    for (const auto& c : r.steps.back().contacts) {
      if (c.element >= 0) EXPECT_GT(c.force, 0.0) << normal << ": a point in touch pushes";
      total += c.force;
      std::printf("[figure] 5 elements, %s normal: element %d force %.8g\n", normal, c.element, c.force);
    }
    std::printf("[figure] exact: %.8g %.8g\n", exact[0], exact[1]);
    EXPECT_GT(total, P) << normal << ": the points carry more than the tip load (the root pulls down)";
    expect_equilibrium(model, r.steps.back());
  }
}

TEST(RestingCantileverNormal, APointWithinAnElementSettlesOnEveryMesh) {
  // One rigid point at (0.47, −0.05) L, inside an element on every mesh: along the bent beam's
  // normal the force is within 5·10⁻⁵ of the exact elastica's with 5 … 80 elements. (A point that
  // has just touched pushes along the chord's normal until the next update, ContactState::entering:
  // without that, its first Y, read from how far the predictor ran the beam through the point,
  // turned its normal half a radian and the 80-element mesh never settled.)
  const double P = 10.0;
  const std::vector<Eigen::Vector2d> point = {{0.47, -0.05}};
  const double exact = resting_cantilever_forces(P, point)[0];
  for (int divisions : {5, 10, 20, 40, 80}) {
    tsm::Model model;
    const RunResult r = run(resting_cantilever(divisions, P, point, "deflected"), model);
    ASSERT_EQ(r.status, tsm::solver::Status::converged) << divisions << ": " << r.message;
    const double error = contact_of(r.steps.back()).force / exact - 1.0;
    std::printf("[figure] %d elements: contact force %.8g, exact %.8g, error %+.2e\n", divisions,
                contact_of(r.steps.back()).force, exact, error);
    EXPECT_LT(std::abs(error), 5e-5) << divisions;
  }
}

INSTANTIATE_TEST_SUITE_P(Formulations, LargePush,
                         ::testing::Values(PushCase{"euler-bernoulli", "chord"}, PushCase{"timoshenko", "chord"},
                                           PushCase{"euler-bernoulli", "cantilever"}, PushCase{"timoshenko", "cantilever"}));

}  // namespace
