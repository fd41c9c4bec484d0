// The three-node contact element (FORMULATION §2): the force law against the checked unit-test
// values, the point-load split against the matrix form, the full tangent (sliding term included)
// against central finite differences at large rigid rotations, self-equilibrium, rigid motion.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include "support/contact_trial.hpp"
#include "tsmframe/contact/contact_response.hpp"

namespace {

using namespace tsm::contact;
using tsm::element::Matrix3;
using tsm::element::SectionStiffness;
constexpr double pi = std::numbers::pi;

TEST(ContactForceLaw, EulerBernoulliMatchesCheckedValues) {
  // FORMULATION §2: EI = 1, l0 = 0.5, α = 0.3.
  const Matrix3 k = contact_bending_stiffness({.EA = 1.0, .EI = 1.0, .shear_flexibility = 0.0}, 0.5, 0.3);
  EXPECT_NEAR(k(0, 0), 22.0, 1e-9);
  EXPECT_NEAR(k(0, 1), -2.0, 1e-9);
  EXPECT_NEAR(k(0, 2), -190.47619048, 1e-7);
  EXPECT_NEAR(k(1, 1), 10.571428571, 1e-8);
  EXPECT_NEAR(k(1, 2), 81.632653061, 1e-8);
  EXPECT_NEAR(k(2, 2), 2591.5127956, 1e-6);
  EXPECT_TRUE(k.isApprox(k.transpose(), 1e-15));
}

TEST(ContactForceLaw, TimoshenkoMatchesCheckedValues) {
  const Matrix3 k = contact_bending_stiffness({.EA = 1.0, .EI = 1.0, .shear_flexibility = 0.01}, 0.5, 0.3);
  EXPECT_NEAR(k(0, 0), 9.1008505468, 1e-9);
  EXPECT_NEAR(k(0, 1), 0.30376670717, 1e-10);
  EXPECT_NEAR(k(0, 2), -45.686512758, 1e-8);
  EXPECT_NEAR(k(1, 1), 7.0595382746, 1e-9);
  EXPECT_NEAR(k(1, 2), 26.245443499, 1e-8);
  EXPECT_NEAR(k(2, 2), 685.06625007, 1e-7);
}

/// The point-load split rebuilt as a 3×3 matrix: k_plain + h hᵀ/c, h/c, 1/c.
Matrix3 split_as_matrix(const SectionStiffness& s, double l0, double alpha) {
  const PointLoadLaw law = point_load_law(s, l0, alpha, 1e-9);
  const Matrix3 k0 = tsm::element::basic_stiffness(s, l0);
  const Eigen::Vector3d v(law.h_i, law.h_j, 1.0);
  Matrix3 k = v * v.transpose() / law.compliance;
  k.topLeftCorner<2, 2>() += k0.bottomRightCorner<2, 2>();
  return k;
}

TEST(ContactForceLaw, PointLoadSplitEqualsEquationSixAndSeven) {
  for (double psi : {0.0, 0.004, 0.05})
    for (double alpha : {0.01, 0.3, 0.5, 0.77, 0.999}) {
      const SectionStiffness s{.EA = 1.0, .EI = 2.5, .shear_flexibility = psi};
      const Matrix3 reference = contact_bending_stiffness(s, 0.7, alpha);
      EXPECT_LT((split_as_matrix(s, 0.7, alpha) - reference).norm(), 1e-9 * reference.norm())
          << "psi " << psi << " alpha " << alpha;
    }
}

TEST(ContactForceLaw, DerivativesInAlphaMatchFiniteDifferences) {
  for (double psi : {0.0, 0.02}) {
    const SectionStiffness s{.EA = 1.0, .EI = 1.7, .shear_flexibility = psi};
    for (double alpha : {0.1, 0.45, 0.8}) {
      const double h = 1e-6;
      const PointLoadLaw at = point_load_law(s, 0.6, alpha, 1e-3);
      const PointLoadLaw up = point_load_law(s, 0.6, alpha + h, 1e-3), down = point_load_law(s, 0.6, alpha - h, 1e-3);
      EXPECT_NEAR(at.dh_i, (up.h_i - down.h_i) / (2 * h), 1e-7);
      EXPECT_NEAR(at.dh_j, (up.h_j - down.h_j) / (2 * h), 1e-7);
      EXPECT_NEAR(at.dcompliance, (up.compliance - down.compliance) / (2 * h), 1e-7 * std::abs(at.dcompliance) + 1e-14);
    }
  }
}

TEST(ContactForceLaw, FreeShapeAndMomentsVanishAtTheEnds) {
  // A point force at a beam node loads nothing but that node: h = 0 there, for both theories.
  for (double psi : {0.0, 0.03})
    for (double alpha : {0.0, 1.0}) {
      const PointLoadLaw law = point_load_law({.EA = 1.0, .EI = 1.0, .shear_flexibility = psi}, 0.5, alpha, 1e-2);
      EXPECT_EQ(law.h_i, 0.0);
      EXPECT_EQ(law.h_j, 0.0);
      EXPECT_GT(law.compliance, 0.0);
    }
}

TEST(ContactForceLaw, ComplianceFloorHoldsWithinTheEdgeZone) {
  // Euler–Bernoulli: clamped within δ l0 of a node to c_min = (δ(1−δ) l0)³ / 3EI.
  const SectionStiffness eb{.EA = 1.0, .EI = 2.0, .shear_flexibility = 0.0};
  const double c_min = std::pow(0.01 * 0.99 * 0.5, 3) / (3.0 * 2.0);
  for (double alpha : {0.0, 0.004, 0.995, 1.0}) {
    const PointLoadLaw law = point_load_law(eb, 0.5, alpha, 0.01);
    EXPECT_EQ(law.compliance, c_min) << alpha;
    EXPECT_EQ(law.dcompliance, 0.0) << alpha;
  }
  EXPECT_GT(point_load_law(eb, 0.5, 0.98, 0.01).compliance, c_min);
  // Timoshenko with real shear flexibility: c ≈ b Ψ/EI stays above c_min to within 1e-4 of the node…
  const SectionStiffness shear{.EA = 1.0, .EI = 2.0, .shear_flexibility = 0.01};
  EXPECT_GT(point_load_law(shear, 0.5, 0.9999, 0.01).compliance, c_min);
  EXPECT_NE(point_load_law(shear, 0.5, 0.9999, 0.01).dcompliance, 0.0);
  // … but a negligible Ψ behaves like Euler–Bernoulli.
  const SectionStiffness stiff{.EA = 1.0, .EI = 2.0, .shear_flexibility = 1e-12};
  EXPECT_EQ(point_load_law(stiff, 0.5, 0.999, 0.01).compliance, c_min);
}

TEST(ContactForceLaw, AStiffnessCapFloorsTheComplianceWhereverItBinds) {
  // min_compliance (the contact's max_stiffness_ratio against its node's own elements) is a floor
  // like the edge's: where the point's compliance with both ends held, (α(1−α) l0)³/(3EI), is
  // below it, c is the floor and flat in α; elsewhere the law is untouched.
  const SectionStiffness eb{.EA = 1.0, .EI = 2.0, .shear_flexibility = 0.0};
  const double l0 = 0.5, cap = 1e-5;  // binds where α(1−α) < (3 EI cap)^(1/3) / l0 = 0.0783
  for (double alpha : {0.0, 0.03, 0.08, 0.95, 1.0}) {
    const PointLoadLaw law = point_load_law(eb, l0, alpha, 0.01, cap);
    EXPECT_EQ(law.compliance, cap) << alpha;
    EXPECT_EQ(law.dcompliance, 0.0) << alpha;
    EXPECT_EQ(law.h_i, point_load_law(eb, l0, alpha, 0.01).h_i) << "the free shape is the plain law's";
  }
  for (double alpha : {0.09, 0.3, 0.5, 0.9}) {
    const PointLoadLaw capped = point_load_law(eb, l0, alpha, 0.01, cap), plain = point_load_law(eb, l0, alpha, 0.01);
    EXPECT_NEAR(capped.compliance, std::pow(alpha * (1.0 - alpha) * l0, 3) / (3.0 * 2.0), 1e-15) << alpha;
    EXPECT_GT(capped.compliance, cap) << alpha;
    EXPECT_EQ(capped.compliance, plain.compliance) << alpha;
    EXPECT_EQ(capped.dcompliance, plain.dcompliance) << alpha;
  }
  // Below the edge's floor the cap changes nothing.
  const double c_edge = std::pow(0.01 * 0.99 * l0, 3) / (3.0 * 2.0);
  EXPECT_EQ(point_load_law(eb, l0, 0.0, 0.01, 0.5 * c_edge).compliance, c_edge);
}

// ---- Hinged and sprung ends (connected_law) ----

struct Ends {
  double i, j;  // flexibilities: 0 rigid, ∞ hinge, else 1/k
};
const Ends connections[] = {{INFINITY, 0.0}, {0.0, INFINITY}, {INFINITY, INFINITY}, {0.4, 0.0}, {0.3, 0.7}, {INFINITY, 0.5}};

/// Reference, independent of connected_law: Eq. 6/7's matrix K maps the element's own end
/// rotations and δy_c to (M_i, M_j, Y); at a hinge M = 0, at a spring θ_node = θ_e + f M. Solved
/// for θ_e by a 2×2 system per unit (θ_node,i, θ_node,j, δy_c): the condensed 3×3 map.
Matrix3 condensed_reference(const SectionStiffness& s, double l0, double alpha, Ends f) {
  const Matrix3 K = contact_bending_stiffness(s, l0, alpha);
  const double flex[2] = {f.i, f.j};
  Matrix3 out;
  for (int unit = 0; unit < 3; ++unit) {
    Eigen::Vector3d given = Eigen::Vector3d::Unit(unit);  // (θ_node,i, θ_node,j, δ)
    // rows r: hinge: K(r,0) θe0 + K(r,1) θe1 = −K(r,2) δ; else θe_r + f_r (K(r,·)(θe, δ)) = θn_r
    Eigen::Matrix2d A;
    Eigen::Vector2d b;
    for (int r = 0; r < 2; ++r) {
      if (std::isinf(flex[r])) {
        A.row(r) << K(r, 0), K(r, 1);
        b[r] = -K(r, 2) * given[2];
      } else {
        A.row(r) << (r == 0 ? 1.0 : 0.0) + flex[r] * K(r, 0), (r == 1 ? 1.0 : 0.0) + flex[r] * K(r, 1);
        b[r] = given[r] - flex[r] * K(r, 2) * given[2];
      }
    }
    const Eigen::Vector2d theta_e = A.lu().solve(b);
    out.col(unit) = K * Eigen::Vector3d(theta_e[0], theta_e[1], given[2]);
  }
  return out;
}

TEST(ContactForceLaw, ConnectedLawIsEquationSixAndSevenWithItsEndsCondensed) {
  for (double psi : {0.0, 0.01})
    for (double alpha : {0.15, 0.5, 0.8})
      for (const Ends f : connections) {
        const SectionStiffness s{.EA = 1.0, .EI = 2.5, .shear_flexibility = psi};
        const double l0 = 0.7;
        const ConnectedLaw c = connected_law(point_load_law(s, l0, alpha, 1e-9),
                                             tsm::element::basic_stiffness(s, l0).bottomRightCorner<2, 2>(), f.i, f.j);
        const Eigen::Vector3d v(c.law.h_i, c.law.h_j, 1.0);
        Matrix3 split = v * v.transpose() / c.law.compliance;
        split.topLeftCorner<2, 2>() += c.k_plain;
        const Matrix3 reference = condensed_reference(s, l0, alpha, f);
        EXPECT_LT((split - reference).norm(), 1e-9 * reference.norm()) << "psi " << psi << " alpha " << alpha << " ends " << f.i
                                                                       << " " << f.j << "\n" << split << "\n" << reference;
        // K' is the hinged or sprung element's own bending block (GlobalSystem's Connection::k).
        const Matrix3 element = tsm::element::connected_stiffness(tsm::element::basic_stiffness_terms(s, l0), f.i, f.j);
        EXPECT_LT((c.k_plain - element.bottomRightCorner<2, 2>()).norm(), 1e-12 * element.norm());
        if (std::isinf(f.i)) EXPECT_EQ(c.law.h_i, 0.0);
        if (std::isinf(f.j)) EXPECT_EQ(c.law.h_j, 0.0);
      }
}

TEST(ContactForceLaw, ASimplySupportedElementsPointCompliance) {
  // Both ends hinged, Euler–Bernoulli: a point load at a = α l0 deflects a simply supported span
  // by P a² b² / (3 EI l0); Timoshenko adds P a b / (l0 G A_s) = P a b Ψ / (l0 EI).
  for (double psi : {0.0, 0.02}) {
    const SectionStiffness s{.EA = 1.0, .EI = 1.3, .shear_flexibility = psi};
    const double l0 = 0.9, alpha = 0.35, a = alpha * l0, b = l0 - a;
    const ConnectedLaw c = connected_law(point_load_law(s, l0, alpha, 1e-9),
                                         tsm::element::basic_stiffness(s, l0).bottomRightCorner<2, 2>(), INFINITY, INFINITY);
    EXPECT_NEAR(c.law.compliance, a * a * b * b / (3.0 * s.EI * l0) + a * b * psi / (l0 * s.EI), 1e-12);
  }
}

TEST(ContactForceLaw, ConnectedDerivativesInAlphaMatchFiniteDifferences) {
  for (double psi : {0.0, 0.02})
    for (const Ends f : connections)
      for (double alpha : {0.1, 0.45, 0.8}) {
        const SectionStiffness s{.EA = 1.0, .EI = 1.7, .shear_flexibility = psi};
        const Eigen::Matrix2d k = tsm::element::basic_stiffness(s, 0.6).bottomRightCorner<2, 2>();
        auto at = [&](double x) { return connected_law(point_load_law(s, 0.6, x, 1e-3), k, f.i, f.j).law; };
        const double h = 1e-6;
        const PointLoadLaw law = at(alpha), up = at(alpha + h), down = at(alpha - h);
        EXPECT_NEAR(law.dh_i, (up.h_i - down.h_i) / (2 * h), 1e-7);
        EXPECT_NEAR(law.dh_j, (up.h_j - down.h_j) / (2 * h), 1e-7);
        EXPECT_NEAR(law.dcompliance, (up.compliance - down.compliance) / (2 * h), 1e-7 * std::abs(law.dcompliance) + 1e-12);
      }
}

// ---- The element ----

using Trial = tsm::test::ContactTrial;
using tsm::test::finite_difference_tangent;

/// The element of tests/support/contact_trial.hpp (unshifted, its contact node turned by 0.7).
Trial trial(double psi, double angle, double theta_i, double theta_j, double alpha0, double push, double slide,
            bool sliding_term = true) {
  return tsm::test::contact_trial({.psi = psi, .angle = angle, .theta_i = theta_i, .theta_j = theta_j, .alpha0 = alpha0,
                                   .push = push, .slide = slide, .sliding_term = sliding_term});
}

struct TangentCase {
  double psi, angle, theta_i, theta_j, alpha0, push, slide;
};

class ContactTangent : public ::testing::TestWithParam<TangentCase> {};

TEST_P(ContactTangent, MatchesFiniteDifferencesWithTheSlidingTerm) {
  const TangentCase& p = GetParam();
  const Trial s = trial(p.psi, p.angle, p.theta_i, p.theta_j, p.alpha0, p.push, p.slide);
  const ContactResponse r = contact_response(s.data, s.d, s.previous);
  ASSERT_GT(r.alpha, 0.0);
  ASSERT_LT(r.alpha, 1.0);
  const Matrix9 fd = finite_difference_tangent(s);
  EXPECT_LE((r.tangent - fd).norm(), 1e-6 * fd.norm()) << "analytic\n" << r.tangent << "\nfd\n" << fd;
}

TEST_P(ContactTangent, WithoutTheSlidingTermItIsSymmetricAndMeasurablyOff) {
  const TangentCase& p = GetParam();
  const Trial with = trial(p.psi, p.angle, p.theta_i, p.theta_j, p.alpha0, p.push, p.slide, true);
  const Trial without = trial(p.psi, p.angle, p.theta_i, p.theta_j, p.alpha0, p.push, p.slide, false);
  const Matrix9 K = contact_response(with.data, with.d, with.previous).tangent;
  const Matrix9 Kq = contact_response(without.data, without.d, without.previous).tangent;
  EXPECT_LE((Kq - Kq.transpose()).norm(), 1e-12 * Kq.norm());
  EXPECT_GT((K - Kq).norm(), 1e-4 * K.norm());  // the term matters once the beam is loaded
}

INSTANTIATE_TEST_SUITE_P(
    Cases, ContactTangent,
    ::testing::Values(TangentCase{0.0, 0.0, 0.01, -0.02, 0.3, 1e-3, 0.0},         // EB, small
                      TangentCase{0.0, 2.5, 0.2, -0.1, 0.6, 2e-2, 0.05},          // EB, rotated 2.5 rad
                      TangentCase{0.0, -3.0 * pi + 0.4, -0.3, 0.25, 0.2, -1e-2, 0.1},  // EB, −3π
                      TangentCase{0.01, 0.0, 0.01, -0.02, 0.5, 1e-3, 0.0},        // Timoshenko
                      TangentCase{0.01, 4.0, 0.3, 0.1, 0.7, 3e-2, 0.1},           // Timoshenko, 4 rad
                      TangentCase{0.002, -1.0, 0.1, -0.2, 0.9, 5e-3, 0.05}));      // near the end

TEST(ContactElement, HingedOrSprungTangentMatchesFiniteDifferencesAndAHingeCarriesNoMoment) {
  for (const Ends f : connections)
    for (const TangentCase& p : {TangentCase{0.0, 2.5, 0.2, -0.1, 0.6, 2e-2, 0.05}, TangentCase{0.01, 4.0, 0.3, 0.1, 0.3, 3e-2, 0.1}}) {
      Trial s = trial(p.psi, p.angle, p.theta_i, p.theta_j, p.alpha0, p.push, p.slide);
      s.data.flexibility_i = f.i;
      s.data.flexibility_j = f.j;
      const ContactResponse r = contact_response(s.data, s.d, s.previous);
      const Matrix9 fd = finite_difference_tangent(s);
      EXPECT_LE((r.tangent - fd).norm(), 1e-6 * fd.norm()) << "ends " << f.i << " " << f.j << "\nanalytic\n" << r.tangent << "\nfd\n" << fd;
      if (std::isinf(f.i)) EXPECT_EQ(r.forces[1], 0.0);
      if (std::isinf(f.j)) EXPECT_EQ(r.forces[2], 0.0);
      EXPECT_NE(r.forces[3], 0.0);
      // A hinged end's node turns freely: its rotation moves no force.
      if (std::isinf(f.i)) EXPECT_EQ(r.tangent.col(2).norm(), 0.0);
    }
}

TEST(ContactElement, ForcesAreSelfEquilibrated) {
  for (double psi : {0.0, 0.01}) {
    const Trial s = trial(psi, 1.3, 0.2, -0.15, 0.4, 0.03, 0.05);
    const ContactResponse r = contact_response(s.data, s.d, s.previous);
    ASSERT_GT(std::abs(r.forces[3]), 1.0);  // a real contact force
    const Vector9& F = r.nodal_forces;
    const double scale = F.cwiseAbs().maxCoeff();
    EXPECT_NEAR(F[0] + F[3] + F[6], 0.0, 1e-12 * scale);
    EXPECT_NEAR(F[1] + F[4] + F[7], 0.0, 1e-12 * scale);
    // Moments about the origin, at the current positions.
    const Eigen::Vector2d xi = s.data.initial.start + s.d.segment<2>(0), xj = s.data.initial.end + s.d.segment<2>(3),
                          xc = s.data.contact_start + s.d.segment<2>(6);
    auto cross = [](const Eigen::Vector2d& x, double fx, double fy) { return x.x() * fy - x.y() * fx; };
    const double moment = F[2] + F[5] + F[8] + cross(xi, F[0], F[1]) + cross(xj, F[3], F[4]) + cross(xc, F[6], F[7]);
    EXPECT_NEAR(moment, 0.0, 1e-12 * scale * 3.0);
    EXPECT_EQ(F[8], 0.0);  // the contact node takes no moment
  }
}

TEST(ContactElement, RigidMotionMakesNoForce) {
  for (double psi : {0.0, 0.01})
    for (double angle : {0.0, 0.7, -2.9, 5.0 * pi}) {
      Trial s = trial(psi, angle, 0.0, 0.0, 0.35, 0.0, 0.0);
      s.d.head<6>() += (Vector9() << 0.4, -0.3, 0, 0.4, -0.3, 0, 0, 0, 0).finished().head<6>();
      s.d.segment<2>(6) += Eigen::Vector2d(0.4, -0.3);
      // undo the 0.2 % stretch of trial(): rebuild the end and contact exactly rigidly
      const Eigen::Rotation2Dd R(angle);
      const Eigen::Vector2d chord = s.data.initial.end - s.data.initial.start;
      const Eigen::Vector2d xj = s.data.initial.start + Eigen::Vector2d(0.4, -0.3) + R * chord;
      const Eigen::Vector2d xc = s.data.initial.start + Eigen::Vector2d(0.4, -0.3) + 0.35 * (R * chord);
      s.d.segment<2>(3) = xj - s.data.initial.end;
      s.d.segment<2>(6) = xc - s.data.contact_start;
      const ContactResponse r = contact_response(s.data, s.d, s.previous);
      EXPECT_LT(r.nodal_forces.norm(), 1e-9 * 400.0) << "angle " << angle;
      EXPECT_NEAR(r.alpha, 0.35, 1e-13);
    }
}

TEST(ContactElement, ZeroForceOnTheFreeShapeAndNodeOnElementAgrees) {
  // A node placed on the bent element's own free deflection w(α) gets Y = 0, and
  // node_on_element reports gap 0 there — activation starts without a jump in force.
  for (double psi : {0.0, 0.02}) {
    Trial s = trial(psi, 0.8, 0.05, -0.08, 0.4, 0.0, 0.0);
    const ContactResponse straight = contact_response(s.data, s.d, s.previous);
    const PointLoadLaw law = point_load_law(s.data.section, s.data.initial.length, straight.alpha, 1e-3);
    const double w = -(law.h_i * straight.deformations[1] + law.h_j * straight.deformations[2]);
    const Eigen::Vector2d n(-straight.chord.sin, straight.chord.cos);
    s.d.segment<2>(6) += (w - straight.normal) * n;
    const ContactResponse on = contact_response(s.data, s.d, s.previous);
    EXPECT_NEAR(on.forces[3], 0.0, 1e-9 * std::abs(straight.forces[3]) + 1e-9);
    const NodeOnElement where = node_on_element(s.data.initial, s.data.section, s.d.head<6>(), s.previous,
                                                s.data.contact_start + s.d.segment<2>(6));
    EXPECT_NEAR(where.gap, 0.0, 1e-14);
    EXPECT_NEAR(where.alpha, on.alpha, 1e-14);
  }
}

TEST(ContactElement, HingedOrSprungZeroForceOnTheFreeShapeAndNodeOnElementAgrees) {
  // As above with the element's ends connected through hinges or springs: its free deflection
  // follows the nodes' rotations through the connections (none through a hinge).
  for (const Ends f : connections) {
    Trial s = trial(0.01, 0.8, 0.05, -0.08, 0.4, 0.0, 0.0);
    s.data.flexibility_i = f.i;
    s.data.flexibility_j = f.j;
    const ContactResponse straight = contact_response(s.data, s.d, s.previous);
    const ConnectedLaw c = connected_law(point_load_law(s.data.section, s.data.initial.length, straight.alpha, 1e-3),
                                         s.data.k0.bottomRightCorner<2, 2>(), f.i, f.j);
    const double w = -(c.law.h_i * straight.deformations[1] + c.law.h_j * straight.deformations[2]);
    const Eigen::Vector2d n(-straight.chord.sin, straight.chord.cos);
    s.d.segment<2>(6) += (w - straight.normal) * n;
    const ContactResponse on = contact_response(s.data, s.d, s.previous);
    EXPECT_NEAR(on.forces[3], 0.0, 1e-9 * std::abs(straight.forces[3]) + 1e-9);
    const NodeOnElement where = node_on_element(s.data.initial, s.data.section, s.d.head<6>(), s.previous,
                                                s.data.contact_start + s.d.segment<2>(6), f.i, f.j);
    EXPECT_NEAR(where.gap, 0.0, 1e-14);
  }
}

}  // namespace
