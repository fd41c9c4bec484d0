// The k-point contact element with the forces along the deflected normal (docs/contact-normal.md
// §8, multi_point_deflected_normal): the clamped influence function's second derivatives (N17)
// against central differences; k = 1 is deflected_normal_response in every field; the whole
// tangent (sliding terms included) against central differences, k = 2, 3, 5, bent, both theories,
// rigid, hinged and sprung ends, a pair on the floor, a point beyond an end; a straight unloaded
// element is the chord's-normal element; each force is normal to the shape's tangent at its
// point, that tangent taken from the law itself; self-equilibrium and rigid motion.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "support/contact_trial.hpp"
#include "support/end_connections.hpp"
#include "support/multi_point_trial.hpp"
#include "tsmframe/contact/contact_element.hpp"
#include "tsmframe/contact/deflected_normal_element.hpp"
#include "tsmframe/contact/multi_point_deflected_normal.hpp"
#include "tsmframe/contact/multi_point_law.hpp"

namespace {

using namespace tsm::contact;
using tsm::test::connections;
using tsm::test::describe;
using tsm::test::Ends;
using tsm::test::MultiSpec;
using tsm::test::MultiTrial;

/// The trial element with every point's force along the bent beam's normal, but `chord_points`'.
MultiTrial deflected_trial(MultiSpec p) {
  p.normal = tsm::ContactNormal::deflected;
  return tsm::test::multi_trial(p);
}

MultiPointResponse respond(const MultiTrial& s, bool with_tangent = true) {
  return multi_point_deflected_response(s.data, s.d, s.previous, with_tangent);
}

Eigen::MatrixXd tangent_by_differences(const MultiTrial& s, double h = 1e-6) {
  return tsm::test::multi_point_finite_difference_tangent(s, multi_point_deflected_response, h);
}

// ---- N17: the clamped influence function's second derivatives ----

/// f'(at) on [0, l0] by differences of step 1e-5: central inside, one-sided (second order) at an end.
template <class F>
double derivative(F f, double at, double l0) {
  const double h = 1e-5;
  if (at == 0.0) return (-3.0 * f(0.0) + 4.0 * f(h) - f(2 * h)) / (2 * h);
  if (at == l0) return (3.0 * f(l0) - 4.0 * f(l0 - h) + f(l0 - 2 * h)) / (2 * h);
  return (f(at + h) - f(at - h)) / (2 * h);
}

TEST(MultiPointDeflectedNormal, InfluenceSecondDerivativesMatchDifferencesOfTheSlope) {
  double worst = 0.0;
  for (double psi : {0.0, 0.004, 0.05}) {
    const tsm::element::SectionStiffness section{.EA = 400.0, .EI = 3.0, .shear_flexibility = psi};
    const double l0 = 1.2, scale = l0 / section.EI;  // ∂²C/∂x² ~ l0/EI
    for (double x : {0.0, 0.05, 0.3, 0.61, 0.9, 1.2})
      for (double xi : {0.0, 0.1, 0.45, 0.62, 1.15, 1.2}) {
        if (std::abs(x - xi) < 2e-3) continue;  // the slope jumps there for Timoshenko
        auto slope = [&](double a, double b) { return clamped_influence_slope(section, l0, a, b); };
        const double xx = derivative([&](double a) { return slope(a, xi); }, x, l0);
        const double xxi = derivative([&](double b) { return slope(x, b); }, xi, l0);
        const double a = clamped_influence_curvature(section, l0, x, xi), b = clamped_influence_cross_slope(section, l0, x, xi);
        EXPECT_LE(std::abs(a - xx), 1e-8 * scale) << psi << " " << x << " " << xi;
        EXPECT_LE(std::abs(b - xxi), 1e-8 * scale) << psi << " " << x << " " << xi;
        worst = std::max({worst, std::abs(a - xx) / scale, std::abs(b - xxi) / scale});
      }
    // Continuous where the points meet; 0 beyond the ends (ξ clamped for ∂²C/∂x²).
    for (double x : {0.2, 0.7}) {
      EXPECT_NEAR(clamped_influence_curvature(section, l0, x, x), clamped_influence_curvature(section, l0, x, x + 1e-9),
                  1e-7 * scale);
      EXPECT_NEAR(clamped_influence_curvature(section, l0, x, x), clamped_influence_curvature(section, l0, x, x - 1e-9),
                  1e-7 * scale);
      EXPECT_NEAR(clamped_influence_cross_slope(section, l0, x, x), clamped_influence_cross_slope(section, l0, x, x + 1e-9),
                  1e-7 * scale);
      EXPECT_NEAR(clamped_influence_cross_slope(section, l0, x, x), clamped_influence_cross_slope(section, l0, x, x - 1e-9),
                  1e-7 * scale);
    }
    EXPECT_EQ(clamped_influence_curvature(section, l0, 1.3, 0.5), 0.0);
    EXPECT_EQ(clamped_influence_cross_slope(section, l0, 0.5, -0.1), 0.0);
    EXPECT_EQ(clamped_influence_curvature(section, l0, 0.5, 1.3), clamped_influence_curvature(section, l0, 0.5, 1.2));
  }
  std::printf("∂²C/∂x², ∂²C/∂x∂ξ against differences of ∂C/∂x: worst %.2e of l0/EI\n", worst);
}

// ---- k = 1 is deflected_normal_response ----

/// max |a − b| / max |b| (against the whole field's scale).
template <class A, class B>
double field_error(const A& a, const B& b) {
  const Eigen::MatrixXd x(a), y(b);
  EXPECT_EQ(x.rows(), y.rows());
  EXPECT_EQ(x.cols(), y.cols());
  if (x.rows() != y.rows() || x.cols() != y.cols()) return 1.0;
  return (x - y).cwiseAbs().maxCoeff() / std::max(y.cwiseAbs().maxCoeff(), 1e-300);
}

TEST(MultiPointDeflectedNormal, OnePointIsTheDeflectedNormalElementInEveryField) {
  double worst = 0.0;
  for (double psi : {0.0, 0.01})
    for (double angle : {0.0, 1.2, -2.6, 7.0})
      for (double alpha0 : {0.05, 0.3, 0.62, 0.97, 1.03})  // 1.03: beyond node j, the direction held
        for (const Ends f : {Ends{0.0, 0.0}, connections[0], connections[1], connections[2], connections[4], connections[5]})
          for (bool sliding : {true, false}) {
            tsm::test::ContactTrial t = tsm::test::contact_trial(
                {.psi = psi, .angle = angle, .theta_i = 0.25, .theta_j = -0.15, .alpha0 = alpha0,
                 .push = alpha0 > 1.0 ? 1e-8 : 1.5e-2,  // beyond the end the floor binds: as stiff as c_floor
                 .slide = alpha0 > 1.0 ? 0.0 : 0.01, .sliding_term = sliding});
            t.data.flexibility_i = f.i;
            t.data.flexibility_j = f.j;
            const ContactResponse one = deflected_normal_response(t.data, t.d, t.previous);
            const MultiPointElementData data{.initial = t.data.initial, .section = t.data.section, .k0 = t.data.k0,
                                             .points = {{t.data.contact_start, t.data.offset, tsm::ContactNormal::deflected}}, .edge = t.data.edge,
                                             .min_compliance = t.data.min_compliance, .sliding_term = sliding,
                                             .flexibility_i = f.i, .flexibility_j = f.j};
            const MultiPointResponse r = multi_point_deflected_response(data, t.d, t.previous);
            SCOPED_TRACE("psi " + std::to_string(psi) + " angle " + std::to_string(angle) + " alpha " +
                         std::to_string(alpha0) + " ends " + std::to_string(f.i) + " " + std::to_string(f.j));
            const DeflectedNormal normal = deflected_normal(t.data, one);
            if (alpha0 < 1.0) {  // beyond node j of a beam hinged at both ends, nothing bends it
              ASSERT_GT(std::abs(normal.slope), 1e-3) << "a real slope";
            }
            EXPECT_EQ(r.alpha[0], one.alpha);
            EXPECT_EQ(r.deformations, Eigen::VectorXd(one.deformations));
            const double errors[] = {
                field_error(r.forces, one.forces),
                field_error(r.nodal_forces, one.nodal_forces),
                field_error(r.point_u, one.point_u),
                field_error(r.point_stiffness, Eigen::Matrix<double, 1, 1>(one.point_stiffness)),
                field_error(r.tangent, one.tangent),
                field_error(r.symmetric_tangent, one.symmetric_tangent),
                field_error(r.sliding_u * r.sliding_v.transpose(), one.sliding_u * one.sliding_v.transpose()),
                field_error(r.sliding_v, one.sliding_v),
                field_error(r.force_per_Y, Eigen::Matrix<double, 1, 1>(normal.direction.norm())),
                field_error(multi_point_shape_slopes(data, r) / r.chord.length, Eigen::Matrix<double, 1, 1>(normal.slope))};
            for (int field = 0; field < 10; ++field) {
              EXPECT_LE(errors[field], 1e-12) << "field " << field;
              worst = std::max(worst, errors[field]);
            }
          }
  std::printf("k = 1 against deflected_normal_response: worst relative difference %.2e\n", worst);
}

// ---- The whole tangent against finite differences ----

class MultiPointDeflectedTangent : public ::testing::TestWithParam<MultiSpec> {};

TEST_P(MultiPointDeflectedTangent, MatchesFiniteDifferencesWithTheSlidingTerms) {
  double worst = 0.0;
  for (const Ends f : {Ends{0.0, 0.0}, connections[0], connections[1], connections[2], connections[3], connections[4],
                       connections[5]}) {
    MultiSpec p = GetParam();
    p.ends = f;
    const MultiTrial s = deflected_trial(p);
    const int k = s.data.size();
    const MultiPointResponse r = respond(s);
    ASSERT_GT(r.forces.tail(k).cwiseAbs().minCoeff(), 0.05) << "every point loaded";
    ASSERT_GT((multi_point_shape_slopes(s.data, r) / r.chord.length).cwiseAbs().maxCoeff(), 1e-2) << "a bent shape";
    // A point beyond an end sits on the compliance floor and, for Timoshenko, its Y turns its own
    // normal (½ c_α Y, c_α ≠ 0 at an end): its forces curve within a step of c_floor·|Y| / c_α.
    const bool beyond = (r.alpha.array() < 0.0).any() || (r.alpha.array() > 1.0).any();
    const Eigen::MatrixXd fd = tangent_by_differences(s, beyond ? 1e-9 : 1e-6);
    const double error = (r.tangent - fd).norm() / fd.norm();
    worst = std::max(worst, error);
    EXPECT_LE(error, 1e-6) << describe(p) << "\nanalytic\n" << r.tangent << "\nfd\n" << fd;
    // The split: a symmetric part and one rank-one sliding term per point, along ∂α_p/∂x.
    EXPECT_LE((r.symmetric_tangent - r.symmetric_tangent.transpose()).norm(), 1e-12 * r.tangent.norm()) << describe(p);
    EXPECT_LE((r.tangent - r.symmetric_tangent - r.sliding_u * r.sliding_v.transpose()).norm(), 1e-13 * r.tangent.norm());
    const MultiPointResponse chord = multi_point_response(s.data, s.d, s.previous);
    EXPECT_EQ(r.sliding_v, chord.sliding_v);
    // Without the sliding terms: the symmetric part alone, measurably off.
    MultiTrial without = s;
    without.data.sliding_term = false;
    const MultiPointResponse q = respond(without);
    EXPECT_EQ((q.tangent - r.symmetric_tangent).norm(), 0.0);
    EXPECT_EQ(q.sliding_u.norm(), 0.0);
    EXPECT_GT((r.tangent - q.tangent).norm(), 1e-4 * r.tangent.norm());
  }
  std::printf("tangent against central differences: worst ‖K − K_fd‖/‖K_fd‖ %.2e\n", worst);
}

/// The common cases and, along the bent beam's normal, points at an element end and mixed elements.
std::vector<MultiSpec> deflected_cases() {
  std::vector<MultiSpec> cases = tsm::test::bent_and_turned_cases();
  const std::vector<MultiSpec> more = {
      // a point just beyond node j: its direction held at the end's, its α-rates 0
      MultiSpec{.psi = 0.01, .angle = 1.5, .theta_i = 0.2, .theta_j = -0.3, .alpha0 = {0.35, 1.0},
                .push = {2e-2, 1e-8}, .slide = {0.0, 0.02}},
      MultiSpec{.psi = 0.0, .angle = -1.1, .theta_i = 0.25, .theta_j = 0.15, .alpha0 = {0.0, 0.4, 0.75},
                .push = {-1e-8, -2e-2, -1e-2}, .slide = {-0.02, 0.0, 0.0}},
      // mixed elements: points kept along the chord's normal beside points along the bent beam's
      MultiSpec{.psi = 0.0, .angle = 1.2, .theta_i = 0.2, .theta_j = -0.1, .alpha0 = {0.15, 0.45, 0.8},
                .push = {1e-2, 3e-2, 1.5e-2}, .slide = {0.02, -0.05, 0.03}, .chord_points = {1}},
      MultiSpec{.psi = 0.01, .angle = -1.7, .theta_i = -0.2, .theta_j = 0.3, .alpha0 = {0.2, 0.5, 0.7},
                .push = {-1e-2, -2e-2, -1e-2}, .slide = {0.0, 0.03, -0.02}, .chord_points = {0, 2}}};
  cases.insert(cases.end(), more.begin(), more.end());
  return cases;
}

INSTANTIATE_TEST_SUITE_P(Cases, MultiPointDeflectedTangent, ::testing::ValuesIn(deflected_cases()), tsm::test::case_name);

TEST(MultiPointDeflectedNormal, OnAMixedElementAChordPointPushesAlongTheChordsNormalAndTheOthersAlongTheShapes) {
  for (double psi : {0.0, 0.01}) {
    const MultiTrial s = deflected_trial({.psi = psi, .angle = 1.2, .theta_i = 0.2, .theta_j = -0.1, .alpha0 = {0.15, 0.45, 0.8},
                                          .push = {1e-2, 3e-2, 1.5e-2}, .slide = {0.0, 0.0, 0.0}, .chord_points = {1}});
    const MultiPointResponse r = respond(s);
    const MultiTrial all = deflected_trial({.psi = psi, .angle = 1.2, .theta_i = 0.2, .theta_j = -0.1,
                                            .alpha0 = {0.15, 0.45, 0.8}, .push = {1e-2, 3e-2, 1.5e-2}, .slide = {0.0, 0.0, 0.0}});
    const Eigen::VectorXd w = multi_point_shape_slopes(all.data, respond(all)) / r.chord.length;
    const Eigen::Vector2d e(r.chord.cos, r.chord.sin), n(-r.chord.sin, r.chord.cos);
    for (int p = 0; p < 3; ++p) {
      const Eigen::Vector2d force = r.nodal_forces.segment<2>(6 + 3 * p);
      const double Y = r.forces[3 + p];
      // point 1: Y n exactly; points 0 and 2: Y (n − w' e), w' the bent shape's slope (N3), not 0
      const Eigen::Vector2d expected = p == 1 ? Eigen::Vector2d(Y * n) : Eigen::Vector2d(Y * (n - w[p] * e));
      EXPECT_LE((force - expected).norm(), 1e-12 * std::abs(Y)) << "psi " << psi << " point " << p;
      EXPECT_GT(std::abs(w[p]), 1e-2) << "a bent shape at point " << p;
      EXPECT_NEAR(r.force_per_Y[p], p == 1 ? 1.0 : std::sqrt(1.0 + w[p] * w[p]), 1e-12);
    }
  }
}

TEST(MultiPointDeflectedNormal, TangentWithAPairOnTheFloorMatchesFiniteDifferences) {
  // Two points 5e-4 apart: the pair floor binds in the law (K11); the direction reads the raw beam.
  double worst = 0.0;
  for (double psi : {0.0, 1e-6, 0.01})
    for (const Ends f : {Ends{0.0, 0.0}, connections[4]}) {
      MultiTrial s = deflected_trial({.psi = psi, .angle = 1.3, .theta_i = 0.2, .theta_j = -0.1, .alpha0 = {0.4, 0.4005, 0.7},
                                  .push = {2e-2, 2.1e-2, 1e-2}, .slide = {0.0, 0.0, 0.0}, .ends = f});
      s.data.edge = 1e-2;
      const MultiPointResponse r = respond(s);
      // Timoshenko's pair compliance varies on the scale of the distance (EB's more slowly): a step
      // well inside it, but no smaller than rounding (the floored C is ill-conditioned) allows.
      const Eigen::MatrixXd fd = tangent_by_differences(s, psi > 1e-4 ? 1e-7 : 1e-6);
      const double error = (r.tangent - fd).norm() / fd.norm();
      worst = std::max(worst, error);
      EXPECT_LE(error, 1e-6) << "psi " << psi;
    }
  std::printf("a pair on the floor: worst ‖K − K_fd‖/‖K_fd‖ %.2e\n", worst);
}

// ---- A straight, unloaded element is the chord's-normal element ----

TEST(MultiPointDeflectedNormal, StraightUnloadedElementIsTheChordElementInEveryField) {
  double worst = 0.0;
  for (double psi : {0.0, 0.01})
    for (double angle : {0.0, 1.2, -2.6})
      for (const Ends f : {Ends{0.0, 0.0}, connections[0], connections[2], connections[4]}) {
        const MultiTrial s = deflected_trial({.psi = psi, .angle = angle, .alpha0 = {0.2, 0.5, 0.8}, .push = {0.0, 0.0, 0.0},
                                          .slide = {0.04, -0.03, 0.0}, .ends = f});
        const MultiPointResponse r = respond(s), chord = multi_point_response(s.data, s.d, s.previous);
        SCOPED_TRACE(describe({.psi = psi, .angle = angle, .ends = f}));
        EXPECT_EQ(r.forces, chord.forces);
        EXPECT_EQ(r.point_stiffness, chord.point_stiffness);
        const double errors[] = {field_error(r.nodal_forces, chord.nodal_forces), field_error(r.point_u, chord.point_u),
                                 field_error(r.tangent, chord.tangent),
                                 field_error(r.symmetric_tangent, chord.symmetric_tangent),
                                 field_error(r.sliding_v, chord.sliding_v),
                                 field_error(r.force_per_Y, chord.force_per_Y)};
        for (double e : errors) {
          EXPECT_LE(e, 1e-14);
          worst = std::max(worst, e);
        }
        // sliding_u is rounding on both sides (Y and ∂Y/∂α vanish): against the tangent's scale.
        const double sliding = (r.sliding_u - chord.sliding_u).cwiseAbs().maxCoeff() * chord.sliding_v.norm() /
                               chord.tangent.cwiseAbs().maxCoeff();
        EXPECT_LE(sliding, 1e-14);
        worst = std::max(worst, sliding);
      }
  std::printf("straight and unloaded, against multi_point_response: worst %.2e of a field\n", worst);
}

// ---- Each force is normal to the deflected shape at its point ----

/// The beam's transverse deflection at s (α-units) in the state of r: the law itself with an extra
/// point at s that carries no force (K2 with the connections, K12), δy_s = −h'(s)ᵀ θ + Σ_q C''_sq Y_q
/// — the shape, not the slope formula under test.
double deflection(const MultiTrial& s, const MultiPointResponse& r, double at) {
  const int k = s.data.size();
  Eigen::VectorXd alpha(k + 1);
  alpha << r.alpha, at;
  const double l0 = s.data.initial.length;
  MultiPointLaw law = multi_point_law(s.data.section, l0, alpha, 1e-9);  // no floor in reach
  if (s.data.connected())
    law = connected_multi_point_law(law, s.data.k0.bottomRightCorner<2, 2>(), s.data.flexibility_i, s.data.flexibility_j).law;
  return -law.h.col(k).dot(r.deformations.segment<2>(1)) + law.compliance.row(k).head(k).dot(r.forces.tail(k));
}

TEST(MultiPointDeflectedNormal, EachForceIsNormalToTheShapesTangentAtItsPoint) {
  double worst = 0.0, worst_slope = 0.0, off_chord_normal = 0.0;
  for (double psi : {0.0, 0.01})
    for (const MultiSpec& p : {MultiSpec{.angle = 1.4, .theta_i = 0.2, .theta_j = -0.1, .alpha0 = {0.25, 0.6},
                                         .push = {2e-2, 1e-2}, .slide = {0.0, 0.0}},
                               MultiSpec{.angle = -2.2, .theta_i = -0.1, .theta_j = -0.3, .alpha0 = {0.15, 0.45, 0.8},
                                         .push = {-1e-2, -2e-2, 1e-2}, .slide = {0.02, 0.0, -0.03}},
                               MultiSpec{.angle = 0.3, .theta_i = 0.3, .theta_j = 0.2, .alpha0 = {0.1, 0.3, 0.5, 0.7, 0.9},
                                         .push = {1e-2, 2e-2, 3e-2, 2e-2, 1e-2}, .slide = {0.0, 0.0, 0.0, 0.0, 0.0}}})
      for (const Ends f : {Ends{0.0, 0.0}, connections[0], connections[1], connections[2], connections[4], connections[5]}) {
        MultiSpec spec = p;
        spec.psi = psi;
        spec.ends = f;
        const MultiTrial s = deflected_trial(spec);
        const MultiPointResponse r = respond(s, false);
        const Eigen::VectorXd slopes = multi_point_shape_slopes(s.data, r);
        const Eigen::Vector2d e(r.chord.cos, r.chord.sin), n(-r.chord.sin, r.chord.cos);
        SCOPED_TRACE(describe(spec));
        for (int q = 0; q < s.data.size(); ++q) {
          // Cubic on either side of α_q with a continuous curvature: the central difference is the
          // mean of the one-sided slopes plus K ε², which Richardson removes (ε well inside the
          // distance to the next point).
          auto central = [&](double eps) {
            return (deflection(s, r, r.alpha[q] + eps) - deflection(s, r, r.alpha[q] - eps)) / (2 * eps);
          };
          const double w_alpha = (4.0 * central(0.025) - central(0.05)) / 3.0;
          const Eigen::Vector2d tangent = r.chord.length * e + w_alpha * n;
          const Eigen::Vector2d force = r.nodal_forces.segment<2>(6 + 3 * q);
          const double along = std::abs(force.dot(tangent)) / (force.norm() * tangent.norm());
          EXPECT_LE(along, 1e-10) << "point " << q;
          EXPECT_NEAR(slopes[q], w_alpha, 1e-10 * s.data.initial.length) << "point " << q;
          EXPECT_NEAR(force.norm(), std::abs(r.forces[3 + q]) * r.force_per_Y[q], 1e-13 * force.norm());
          worst = std::max(worst, along);
          worst_slope = std::max(worst_slope, std::abs(slopes[q] - w_alpha) / s.data.initial.length);
          off_chord_normal = std::max(off_chord_normal, std::abs(force.dot(e)) / force.norm());
        }
      }
  EXPECT_GT(off_chord_normal, 0.05) << "the states bend the element: the forces leave the chord's normal";
  std::printf("forces along the shape's tangent: worst %.2e of the force; slope %.2e l0\n", worst, worst_slope);
}

// ---- Equilibrium and rigid motion ----

TEST(MultiPointDeflectedNormal, ForcesAreSelfEquilibratedAndRigidMotionMakesNone) {
  double worst = 0.0;
  for (double psi : {0.0, 0.01})
    for (const Ends f : {Ends{0.0, 0.0}, connections[2], connections[4]}) {
      const MultiTrial s = deflected_trial({.psi = psi, .angle = 1.3, .theta_i = 0.2, .theta_j = -0.15,
                                        .alpha0 = {0.2, 0.5, 0.75}, .push = {0.03, 0.02, 0.01}, .slide = {0.0, 0.05, 0.0},
                                        .ends = f});
      const MultiPointResponse r = respond(s);
      ASSERT_GT(r.forces.tail(3).cwiseAbs().minCoeff(), 0.1);
      tsm::test::expect_multi_point_self_equilibrated(s.data, s.d, r.nodal_forces);
      // A translation moves no force: the forces are the same, the tangent blind to it.
      for (int axis = 0; axis < 2; ++axis) {
        MultiTrial moved = s;
        Eigen::VectorXd shift = Eigen::VectorXd::Zero(s.d.size());
        for (int node = 0; node < 5; ++node) shift[3 * node + axis] = 1.0;
        moved.d += 0.37 * shift;
        const double error = (respond(moved, false).nodal_forces - r.nodal_forces).norm() / r.nodal_forces.norm();
        EXPECT_LE(error, 1e-12);
        EXPECT_LE((r.tangent * shift).norm(), 1e-12 * r.tangent.norm());
        worst = std::max({worst, error, (r.tangent * shift).norm() / r.tangent.norm()});
      }
      // A loaded state turned rigidly about the origin: its forces turn with it.
      for (double angle : {0.7, -2.9, 5.0 * M_PI}) {
        const Eigen::Rotation2Dd R(angle);
        MultiTrial turned = s;
        for (int node = 0; node < 5; ++node) {
          const Eigen::Vector2d drawn = node == 0 ? s.data.initial.start
                                        : node == 1 ? s.data.initial.end
                                                    : s.data.points[node - 2].start;
          turned.d.segment<2>(3 * node) = R * (drawn + s.d.segment<2>(3 * node)) - drawn;
          turned.d[3 * node + 2] += angle;
        }
        turned.previous += angle;
        const Eigen::VectorXd G = respond(turned, false).nodal_forces;
        for (int node = 0; node < 5; ++node) {
          const Eigen::Vector2d expected = R * r.nodal_forces.segment<2>(3 * node);
          EXPECT_LE((G.segment<2>(3 * node) - expected).norm(), 1e-11 * r.nodal_forces.norm()) << angle;
          EXPECT_NEAR(G[3 * node + 2], r.nodal_forces[3 * node + 2], 1e-11 * r.nodal_forces.norm());
        }
      }
    }
  for (double angle : {0.0, 0.7, -2.9}) {  // rigid motion from the drawn state: no force
    MultiTrial s = deflected_trial({.psi = 0.01, .angle = angle, .alpha0 = {0.2, 0.5, 0.75}, .push = {0, 0, 0}, .slide = {0, 0, 0}});
    const Eigen::Rotation2Dd R(angle);
    const Eigen::Vector2d shift(0.4, -0.3), chord = s.data.initial.end - s.data.initial.start;
    s.d.segment<2>(0) = shift;
    s.d.segment<2>(3) = s.data.initial.start + shift + R * chord - s.data.initial.end;
    for (int q = 0; q < 3; ++q)
      s.d.segment<2>(6 + 3 * q) = s.data.initial.start + shift + R * (s.data.points[q].start - s.data.initial.start) -
                                  s.data.points[q].start;
    EXPECT_LT(respond(s).nodal_forces.norm(), 1e-9 * 400.0) << angle;
  }
  std::printf("translation: worst change of the forces, and of the tangent along it, %.2e\n", worst);
}

}  // namespace
