// The contact element's force law (FORMULATION §2, contact_force_law): Eq. 6/7 against the
// checked unit-test values, the point-load split against the matrix form, its derivatives in α,
// the compliance floors (edge zone, stiffness cap), and hinged or sprung ends condensed.
#include <gtest/gtest.h>

#include <cmath>

#include <Eigen/Core>
#include <Eigen/LU>

#include "support/end_connections.hpp"
#include "tsmframe/contact/contact_force_law.hpp"
#include "tsmframe/element/force_law.hpp"

namespace {

using namespace tsm::contact;
using tsm::element::Matrix3;
using tsm::element::SectionStiffness;
using tsm::test::connections;
using tsm::test::Ends;

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

}  // namespace
