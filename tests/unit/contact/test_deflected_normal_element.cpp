// The contact element with the force along the deflected normal (docs/contact-normal.md,
// deflected_normal_element): the shape's slope terms against point_load_law and central
// differences; the whole tangent (sliding term included) against central differences at large
// chord rotations, bent, both theories, rigid, hinged and sprung ends; the chord element where the
// slope is zero; the force on the contact node normal to the shape's tangent, that tangent taken
// from the shape itself (multi_point_law's two-point influence, differenced); on a circular arc
// the direction is the radius to third order in the element size (the chord's: first order);
// self-equilibrium, rigid motion and the axial force on either side of the point.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include <Eigen/Geometry>
#include <Eigen/SVD>

#include "support/contact_trial.hpp"
#include "support/end_connections.hpp"
#include "tsmframe/contact/contact_element.hpp"
#include "tsmframe/contact/deflected_normal_element.hpp"
#include "tsmframe/contact/multi_point_law.hpp"

namespace {

using namespace tsm::contact;
using tsm::test::connections;
using tsm::test::ContactTrial;
using tsm::test::ContactTrialSpec;
using tsm::test::Ends;

/// The element of tests/support/contact_trial.hpp with its ends joined as `ends`.
ContactTrial trial(const ContactTrialSpec& spec, Ends ends = {0.0, 0.0}) {
  ContactTrial t = tsm::test::contact_trial(spec);
  t.data.flexibility_i = ends.i;
  t.data.flexibility_j = ends.j;
  return t;
}

ContactResponse respond(const ContactTrial& t, bool with_tangent = true) {
  return deflected_normal_response(t.data, t.d, t.previous, with_tangent);
}

/// ∂(nodal forces)/∂d by central differences of step h.
Matrix9 tangent_by_differences(const ContactTrial& t, double h = 1e-6) {
  Matrix9 K;
  for (int b = 0; b < 9; ++b) {
    ContactTrial plus = t, minus = t;
    plus.d[b] += h;
    minus.d[b] -= h;
    K.col(b) = (respond(plus, false).nodal_forces - respond(minus, false).nodal_forces) / (2 * h);
  }
  return K;
}

std::string describe(const ContactTrialSpec& p, Ends f) {
  return "psi " + std::to_string(p.psi) + " angle " + std::to_string(p.angle) + " theta " + std::to_string(p.theta_i) +
         " " + std::to_string(p.theta_j) + " alpha " + std::to_string(p.alpha0 + p.slide) + " ends " +
         std::to_string(f.i) + " " + std::to_string(f.j);
}

// ---- The slope's terms (N2, N12) ----

TEST(DeflectedNormal, SlopeTermsArePointLoadLawsDerivativesAndTheirOwn) {
  double worst = 0.0;
  for (double psi : {0.0, 0.004, 0.05})
    for (double alpha : {0.02, 0.3, 0.5, 0.77, 0.99}) {
      const tsm::element::SectionStiffness section{.EA = 400.0, .EI = 3.0, .shear_flexibility = psi};
      const double l0 = 1.2;
      const ShapeSlopeTerms t = shape_slope_terms(section, l0, alpha);
      const PointLoadLaw law = point_load_law(section, l0, alpha, 1e-6);  // the floor far away
      EXPECT_NEAR(t.dh[0], law.dh_i, 1e-14 * std::abs(law.dh_i) + 1e-16);
      EXPECT_NEAR(t.dh[1], law.dh_j, 1e-14 * std::abs(law.dh_j) + 1e-16);
      EXPECT_NEAR(t.dc, law.dcompliance, 1e-13 * std::abs(law.dcompliance) + 1e-18);
      const double h = 1e-5;
      const ShapeSlopeTerms plus = shape_slope_terms(section, l0, alpha + h), minus = shape_slope_terms(section, l0, alpha - h);
      const Eigen::Vector2d ddh = (plus.dh - minus.dh) / (2 * h);
      const double ddc = (plus.dc - minus.dc) / (2 * h);
      // Against their scales, l0 and l0³/EI: next to an end c_αα is small by cancellation.
      const double c_scale = l0 * l0 * l0 / section.EI;
      EXPECT_LE((t.ddh - ddh).norm(), 1e-8 * l0) << psi << " " << alpha;
      EXPECT_LE(std::abs(t.ddc - ddc), 1e-8 * c_scale) << psi << " " << alpha;
      worst = std::max({worst, (t.ddh - ddh).norm() / l0, std::abs(t.ddc - ddc) / c_scale});
    }
  std::printf("second α-derivatives against central differences: worst %.2e of their scale\n", worst);
  // Beyond the ends the direction is held: the end's slope, no second derivatives.
  const tsm::element::SectionStiffness section{.EA = 400.0, .EI = 3.0, .shear_flexibility = 0.01};
  const ShapeSlopeTerms beyond = shape_slope_terms(section, 1.2, 1.03), at = shape_slope_terms(section, 1.2, 1.0);
  EXPECT_EQ(beyond.dh, at.dh);
  EXPECT_EQ(beyond.dc, at.dc);
  EXPECT_EQ(beyond.ddh, Eigen::Vector2d::Zero());
  EXPECT_EQ(beyond.ddc, 0.0);
}

// ---- (a) The whole tangent against finite differences ----

class DeflectedNormalTangent : public ::testing::TestWithParam<ContactTrialSpec> {};

TEST_P(DeflectedNormalTangent, MatchesFiniteDifferencesWithTheSlidingTerm) {
  double worst = 0.0;
  for (const Ends f : {Ends{0.0, 0.0}, connections[0], connections[1], connections[2], connections[3], connections[4],
                       connections[5]}) {
    const ContactTrialSpec& p = GetParam();
    const ContactTrial t = trial(p, f);
    const ContactResponse r = respond(t);
    ASSERT_GT(r.alpha, 0.0);
    ASSERT_LT(r.alpha, 1.0);
    ASSERT_GT(std::abs(r.forces[3]), 0.1) << "a real contact force";
    ASSERT_GT(std::abs(deflected_normal(t.data, r).slope), 1e-3) << "a real slope";
    // The law varies on the scale of the distance b to the nearer end: a step well inside it.
    const double b = std::min(r.alpha, 1.0 - r.alpha) * t.data.initial.length;
    const Matrix9 fd = tangent_by_differences(t, std::min(1e-6, 1e-4 * b));
    const double error = (r.tangent - fd).norm() / fd.norm();
    worst = std::max(worst, error);
    EXPECT_LE(error, 1e-6) << describe(p, f) << "\nanalytic\n" << r.tangent << "\nfd\n" << fd;
    // The split: a symmetric part and the rank-one sliding term along ∂α/∂x.
    EXPECT_LE((r.symmetric_tangent - r.symmetric_tangent.transpose()).norm(), 1e-12 * r.tangent.norm());
    EXPECT_LE((r.tangent - r.symmetric_tangent - r.sliding_u * r.sliding_v.transpose()).norm(), 1e-13 * r.tangent.norm());
    // Without the sliding term: the symmetric part alone, measurably off.
    ContactTrial without = t;
    without.data.sliding_term = false;
    const ContactResponse q = respond(without);
    EXPECT_EQ((q.tangent - r.symmetric_tangent).norm(), 0.0);
    EXPECT_EQ(q.sliding_u.norm(), 0.0);
    EXPECT_GT((r.tangent - q.tangent).norm(), 1e-6 * r.tangent.norm());
  }
  std::printf("tangent against central differences: worst ‖K − K_fd‖/‖K_fd‖ %.2e\n", worst);
}

INSTANTIATE_TEST_SUITE_P(
    Cases, DeflectedNormalTangent,
    ::testing::Values(
        ContactTrialSpec{.psi = 0.0, .angle = 1.0, .theta_i = 0.2, .theta_j = -0.1, .alpha0 = 0.6, .push = 2e-2, .slide = 0.05},
        ContactTrialSpec{.psi = 0.0, .angle = -1.5, .theta_i = -0.3, .theta_j = 0.25, .alpha0 = 0.2, .push = -1e-2, .slide = 0.1},
        ContactTrialSpec{.psi = 0.0, .angle = 2.0, .theta_i = 0.3, .theta_j = 0.3, .alpha0 = 0.45, .push = 3e-2, .slide = -0.05},
        ContactTrialSpec{.psi = 0.01, .angle = 1.3, .theta_i = 0.3, .theta_j = 0.1, .alpha0 = 0.7, .push = 3e-2, .slide = 0.1},
        ContactTrialSpec{.psi = 0.01, .angle = -2.0, .theta_i = -0.2, .theta_j = -0.25, .alpha0 = 0.35, .push = -2e-2, .slide = 0.0},
        ContactTrialSpec{.psi = 0.002, .angle = 1.7, .theta_i = 0.1, .theta_j = -0.2, .alpha0 = 0.9, .push = 5e-3, .slide = 0.05},
        ContactTrialSpec{.psi = 0.0, .angle = -1.2, .theta_i = 0.25, .theta_j = -0.2, .alpha0 = 0.08, .push = 4e-3, .slide = -0.03},
        // within edge·l0 of node j: the compliance floor binds, the direction reads the raw c_α
        ContactTrialSpec{.psi = 0.0, .angle = 1.1, .theta_i = 0.1, .theta_j = -0.15, .alpha0 = 0.9995, .push = 1e-4},
        ContactTrialSpec{.psi = 1e-7, .angle = -1.6, .theta_i = -0.2, .theta_j = 0.1, .alpha0 = 0.0004, .push = -1e-4}),
    [](const ::testing::TestParamInfo<ContactTrialSpec>& info) {
      return std::string(info.param.psi > 0.0 ? "Timoshenko" : "EulerBernoulli") + std::to_string(info.index);
    });

TEST(DeflectedNormal, BeyondAnEndTheDirectionIsHeldAndTheForcesAreContinuous) {
  // An iterate that hands the contact over evaluates the element at α just outside [0, 1].
  double worst = 0.0;
  for (double psi : {0.0, 0.01})
    for (const Ends f : {Ends{0.0, 0.0}, connections[2], connections[4]})
      for (double end : {0.0, 1.0}) {
        auto at = [&](double alpha) {
          return trial({.psi = psi, .angle = 1.4, .theta_i = 0.2, .theta_j = -0.25, .alpha0 = end, .push = 1e-4,
                        .slide = (alpha - end) / 1.002}, f);
        };
        const double outside = end == 0.0 ? -1.0 : 1.0;
        const ContactTrial beyond = at(end + 0.02 * outside);
        const ContactResponse r = respond(beyond);
        ASSERT_GT(std::abs(r.alpha - 0.5), 0.5);
        const Matrix9 fd = tangent_by_differences(beyond);
        EXPECT_LE((r.tangent - fd).norm(), 1e-6 * fd.norm()) << psi << " " << end;
        worst = std::max(worst, (r.tangent - fd).norm() / fd.norm());
        // Across the end neither the direction nor the forces jump: they change in proportion to
        // the step (fast: the floored point is very stiff, and Y is in the direction).
        auto across = [&](double step) {
          const ContactTrial in = at(end - step * outside), out = at(end + step * outside);
          const ContactResponse a = respond(in, false), b = respond(out, false);
          return Eigen::Vector2d((deflected_normal(in.data, a).direction - deflected_normal(out.data, b).direction).norm(),
                                 (a.nodal_forces - b.nodal_forces).norm());
        };
        const Eigen::Vector2d wide = across(1e-9), narrow = across(1e-11);
        EXPECT_LE(narrow[0], 0.02 * wide[0]) << psi << " " << end;
        EXPECT_LE(narrow[1], 0.02 * wide[1]) << psi << " " << end;
      }
  std::printf("beyond an end, tangent against central differences: worst %.2e\n", worst);
}

// ---- (b) Where the slope is zero it is the paper's element ----

/// max |a − b| / max |b| (against the whole field's scale), and the worst of them so far.
double worst_field = 0.0;
template <class A>
double relative(const A& a, const A& b) {
  const double error = (a - b).cwiseAbs().maxCoeff() / std::max(b.cwiseAbs().maxCoeff(), 1e-300);
  worst_field = std::max(worst_field, error);
  return error;
}

TEST(DeflectedNormal, StraightUnloadedElementIsTheChordElementInEveryField) {
  // θ = 0 and the node on the chord: Y = 0, w_α = 0; stretched, turned, the node slid along.
  worst_field = 0.0;
  for (double psi : {0.0, 0.01})
    for (double angle : {0.0, 1.2, -2.6})
      for (const Ends f : {Ends{0.0, 0.0}, connections[0], connections[2], connections[4]}) {
        const ContactTrial t = trial({.psi = psi, .angle = angle, .alpha0 = 0.3, .slide = 0.04}, f);
        const ContactResponse r = respond(t), today = chord_frame_response(t.data, t.d, t.previous);
        SCOPED_TRACE(describe({.psi = psi, .angle = angle, .alpha0 = 0.3, .slide = 0.04}, f));
        EXPECT_EQ(r.forces, today.forces);
        EXPECT_LE(relative(r.nodal_forces, today.nodal_forces), 1e-14);
        EXPECT_LE(relative(r.point_u, today.point_u), 1e-14);
        EXPECT_EQ(r.point_stiffness, today.point_stiffness);
        EXPECT_LE(relative(r.tangent, today.tangent), 1e-14);
        EXPECT_LE(relative(r.symmetric_tangent, today.symmetric_tangent), 1e-14);
        // sliding_u is rounding on both sides here (Y and dY/dα vanish): against the tangent's scale.
        EXPECT_LE((r.sliding_u - today.sliding_u).cwiseAbs().maxCoeff() * today.sliding_v.norm(),
                  1e-14 * today.tangent.cwiseAbs().maxCoeff());
        EXPECT_LE(relative(r.sliding_v, today.sliding_v), 1e-14);
      }
  std::printf("straight and unloaded, against chord_frame_response: worst %.2e of a field\n", worst_field);
}

TEST(DeflectedNormal, PushedAtMidspanOfAStraightElementTheForcesAreTheChordElements) {
  // θ = 0, the point at α = ½ of a symmetric beam: the shape is level there, w_α = 0, so the
  // forces are the chord element's; the tangent differs by the normal's turning alone, the
  // rank-one −Y ∂α/∂x (∇w_α)ᵀ the paper's element lacks.
  worst_field = 0.0;
  double worst_rank = 0.0;
  for (double psi : {0.0, 0.01})
    for (double angle : {0.0, 1.2, -1.9})
      for (const Ends f : {Ends{0.0, 0.0}, Ends{INFINITY, INFINITY}, Ends{0.4, 0.4}}) {
        const ContactTrial t = trial({.psi = psi, .angle = angle, .alpha0 = 0.5, .push = 2e-2}, f);
        const ContactResponse r = respond(t), today = chord_frame_response(t.data, t.d, t.previous);
        SCOPED_TRACE(describe({.psi = psi, .angle = angle, .alpha0 = 0.5}, f));
        ASSERT_GT(std::abs(r.forces[3]), 1.0);
        EXPECT_LE(std::abs(deflected_normal(t.data, r).slope), 1e-14);
        EXPECT_EQ(r.forces, today.forces);
        EXPECT_LE(relative(r.nodal_forces, today.nodal_forces), 1e-14);
        EXPECT_LE(relative(r.point_u, today.point_u), 1e-14);
        const Eigen::JacobiSVD<Matrix9> svd(r.tangent - today.tangent);
        EXPECT_GT(svd.singularValues()[0], 1e-5 * today.tangent.norm()) << "the normal turns";
        EXPECT_LE(svd.singularValues()[1], 1e-12 * today.tangent.norm());
        worst_rank = std::max(worst_rank, svd.singularValues()[1] / today.tangent.norm());
      }
  std::printf("pushed at midspan: forces %.2e of a field; second singular value of the tangent's change %.2e\n",
              worst_field, worst_rank);
}

// ---- (c) The force on the contact node is normal to the deflected shape ----

/// The beam's transverse deflection at s (α-units) under the state of r: its free shape from the
/// nodes' rotations through the end connections plus Y's deflection there (K12's H', C'' with
/// points at α and s) — the shape itself, not the slope formula under test.
double deflection(const ContactTrial& t, const ContactResponse& r, double s) {
  Eigen::VectorXd at(2);
  at << r.alpha, s;
  const double l0 = t.data.initial.length;
  MultiPointLaw law = multi_point_law(t.data.section, l0, at, t.data.edge);
  if (t.data.connected())
    law = connected_multi_point_law(law, t.data.k0.bottomRightCorner<2, 2>(), t.data.flexibility_i, t.data.flexibility_j).law;
  return -law.h.col(1).dot(r.deformations.segment<2>(1)) + law.compliance(0, 1) * r.forces[3];
}

TEST(DeflectedNormal, ForceOnTheContactNodeIsNormalToTheShapesTangent) {
  double worst = 0.0, worst_slope = 0.0, off_chord_normal = 0.0;
  for (double psi : {0.0, 0.01})
    for (const ContactTrialSpec& p : {ContactTrialSpec{.angle = 1.4, .theta_i = 0.2, .theta_j = -0.1, .alpha0 = 0.6, .push = 2e-2},
                                      ContactTrialSpec{.angle = -2.2, .theta_i = -0.1, .theta_j = -0.3, .alpha0 = 0.25, .push = -1e-2},
                                      ContactTrialSpec{.angle = 0.3, .theta_i = 0.3, .theta_j = 0.2, .alpha0 = 0.8, .push = 1e-2}})
      for (const Ends f : {Ends{0.0, 0.0}, connections[0], connections[1], connections[2], connections[4], connections[5]}) {
        ContactTrialSpec spec = p;
        spec.psi = psi;
        const ContactTrial t = trial(spec, f);
        const ContactResponse r = respond(t, false);
        // The shape is a cubic on either side of α with a continuous curvature: its central
        // difference is the mean of the one-sided slopes plus K ε², which Richardson removes.
        auto central = [&](double eps) { return (deflection(t, r, r.alpha + eps) - deflection(t, r, r.alpha - eps)) / (2 * eps); };
        const double w_alpha = (4.0 * central(0.025) - central(0.05)) / 3.0;
        const Eigen::Vector2d e(r.chord.cos, r.chord.sin), n(-r.chord.sin, r.chord.cos);
        const Eigen::Vector2d tangent = r.chord.length * e + w_alpha * n;
        const Eigen::Vector2d force = r.nodal_forces.segment<2>(6);
        const double along = std::abs(force.dot(tangent)) / (force.norm() * tangent.norm());
        SCOPED_TRACE(describe(spec, f));
        EXPECT_LE(along, 1e-12);
        const DeflectedNormal normal = deflected_normal(t.data, r);
        EXPECT_NEAR(normal.slope * r.chord.length, w_alpha, 1e-12 * t.data.initial.length);
        EXPECT_LE((force - r.forces[3] * normal.direction).norm(), 1e-13 * force.norm());
        worst = std::max(worst, along);
        off_chord_normal = std::max(off_chord_normal, std::abs(force.dot(e)) / force.norm());
        worst_slope = std::max(worst_slope, std::abs(normal.slope - w_alpha / r.chord.length));
      }
  EXPECT_GT(off_chord_normal, 0.05) << "the states bend the element: the force leaves the chord's normal";
  std::printf("force on the contact node along the shape's tangent: worst %.2e of the force; slope %.2e\n", worst,
              worst_slope);
}

TEST(DeflectedNormal, OnACircularArcTheDirectionIsTheRadiusToThirdOrderInTheElementSize) {
  // An element drawn straight and bent into an arc of radius 1 (its nodes on the arc, turned to
  // its tangents), a contact node on the arc at 0.3 of its length: the beam's own normal there is
  // the radius. The chord's normal misses it by the slope, O(h); the deflected normal by O(h³).
  for (double psi : {0.0, 1e-4}) {
    double last_chord = 0.0, last_deflected = 0.0;
    for (double h : {0.4, 0.2, 0.1}) {
      ContactElementData data;
      data.initial = tsm::element::initial_chord({0.0, 0.0}, {h, 0.0});
      data.section = {.EA = 1e4, .EI = 1.0, .shear_flexibility = psi};
      data.k0 = tsm::element::basic_stiffness(data.section, h);
      data.edge = 1e-3;
      const double t = 0.3;
      data.contact_start = {t * h, 0.0};
      const Eigen::Vector2d centre(std::sin(h / 2), -std::cos(h / 2));
      auto on_arc = [&](double u) { return Eigen::Vector2d(centre + Eigen::Vector2d(std::sin(h * (u - 0.5)), std::cos(h * (u - 0.5)))); };
      const Eigen::Vector2d xj = on_arc(1.0), xc = on_arc(t), radius = xc - centre;
      Vector9 d;
      d << 0.0, 0.0, h / 2, xj.x() - h, xj.y(), -h / 2, xc.x() - t * h, xc.y(), 0.0;
      const ContactResponse r = deflected_normal_response(data, d, 0.0, false);
      const Eigen::Vector2d nu = deflected_normal(data, r).direction, n(-r.chord.sin, r.chord.cos);
      auto miss = [&](const Eigen::Vector2d& v) { return std::abs(v.x() * radius.y() - v.y() * radius.x()) / v.norm(); };
      const double chord = miss(n), deflected = miss(nu);
      std::printf("arc, psi %g, h %.2f: chord normal off by %.3e rad, deflected normal by %.3e rad\n", psi, h, chord,
                  deflected);
      EXPECT_LT(deflected, 1e-2 * chord);
      if (last_chord > 0.0) {
        EXPECT_NEAR(last_chord / chord, 2.0, 0.05) << "first order";
        EXPECT_GT(last_deflected / deflected, 7.0) << "third order";
      }
      last_chord = chord;
      last_deflected = deflected;
    }
  }
}

// ---- (d) Equilibrium, rigid motion, the axial force on either side ----

TEST(DeflectedNormal, ForcesAreSelfEquilibratedAndSplitTheAxialForceAtThePoint) {
  for (double psi : {0.0, 0.01})
    for (const Ends f : {Ends{0.0, 0.0}, connections[2], connections[4]}) {
      const ContactTrial t = trial({.psi = psi, .angle = 1.3, .theta_i = 0.2, .theta_j = -0.15, .alpha0 = 0.4, .push = 0.03,
                                    .slide = 0.05}, f);
      const ContactResponse r = respond(t);
      ASSERT_GT(std::abs(r.forces[3]), 1.0);
      tsm::test::expect_self_equilibrated(t.data, t.d, r.nodal_forces);
      const Vector9& F = r.nodal_forces;
      const double scale = F.cwiseAbs().maxCoeff();
      // N6: node i is pulled by the axial force on its side of the point, node j by the other's.
      const DeflectedNormal normal = deflected_normal(t.data, r);
      const Eigen::Vector2d e(r.chord.cos, r.chord.sin);
      EXPECT_NEAR(F.segment<2>(0).dot(e), -normal.axial_force_i, 1e-12 * scale);
      EXPECT_NEAR(F.segment<2>(3).dot(e), normal.axial_force_j, 1e-12 * scale);
      EXPECT_NEAR(normal.axial_force_i - normal.axial_force_j, normal.axial_share, 1e-12 * scale);
      EXPECT_NEAR(r.alpha * normal.axial_force_i + (1.0 - r.alpha) * normal.axial_force_j, r.forces[0], 1e-12 * scale);
      // A translation moves no force.
      for (int axis = 0; axis < 2; ++axis) {
        Vector9 shift = Vector9::Zero();
        shift[axis] = shift[3 + axis] = shift[6 + axis] = 1.0;
        EXPECT_LE((r.tangent * shift).norm(), 1e-12 * r.tangent.norm());
      }
    }
}

TEST(DeflectedNormal, RigidMotionMakesNoForceAndTurnsALoadedElementsForces) {
  for (double psi : {0.0, 0.01})
    for (double angle : {0.0, 0.7, -2.9, 5.0 * std::numbers::pi}) {
      // From the drawn state, turned and moved rigidly: no force.
      ContactTrial s = trial({.psi = psi, .angle = angle, .alpha0 = 0.35});
      const Eigen::Rotation2Dd R(angle);
      const Eigen::Vector2d chord = s.data.initial.end - s.data.initial.start, shift(0.4, -0.3);
      s.d.segment<2>(0) = shift;
      s.d.segment<2>(3) = s.data.initial.start + shift + R * chord - s.data.initial.end;
      s.d.segment<2>(6) = s.data.initial.start + shift + 0.35 * (R * chord) - s.data.contact_start;
      s.d[2] = s.d[5] = angle;
      EXPECT_LT(respond(s).nodal_forces.norm(), 1e-9 * 400.0) << "angle " << angle;
      // A loaded, bent state turned by `angle` about the origin: its forces turn with it.
      const ContactTrial t = trial({.psi = psi, .angle = 0.4, .theta_i = 0.2, .theta_j = -0.1, .alpha0 = 0.6, .push = 2e-2, .slide = 0.05},
                                   Ends{0.3, 0.7});
      ContactTrial turned = t;
      const Eigen::Vector2d X[3] = {t.data.initial.start, t.data.initial.end, t.data.contact_start};
      for (int node = 0; node < 3; ++node) {
        const Eigen::Vector2d x = X[node] + t.d.segment<2>(3 * node);
        turned.d.segment<2>(3 * node) = R * x - X[node];
        turned.d[3 * node + 2] += angle;
      }
      turned.previous += angle;
      const Vector9 F = respond(t).nodal_forces, G = respond(turned).nodal_forces;
      for (int node = 0; node < 3; ++node) {
        EXPECT_LE((G.segment<2>(3 * node) - R * F.segment<2>(3 * node)).norm(), 1e-11 * F.norm()) << "angle " << angle;
        EXPECT_NEAR(G[3 * node + 2], F[3 * node + 2], 1e-11 * F.norm());
      }
    }
}

}  // namespace
