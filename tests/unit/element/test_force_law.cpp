// Element force equations (Eq. 3–5): closed-form entries and the limits that tie them together;
// a hinged end (released_stiffness) and end springs in series (connected_stiffness).
#include <gtest/gtest.h>

#include <cmath>

#include <Eigen/Dense>

#include "tsmframe/element/force_law.hpp"

using tsm::element::basic_stiffness;
using tsm::element::basic_stiffness_terms;
using tsm::element::BasicStiffness;
using tsm::element::connected_stiffness;
using tsm::element::Matrix3;
using tsm::element::released_stiffness;
using tsm::element::SectionStiffness;

TEST(ForceLaw, EulerBernoulliIsEquation3) {
  const SectionStiffness s{.EA = 7.0, .EI = 3.0, .shear_flexibility = 0.0};
  const double l0 = 0.5;
  const auto k = basic_stiffness(s, l0);
  EXPECT_DOUBLE_EQ(k(0, 0), 7.0 / l0);
  EXPECT_DOUBLE_EQ(k(1, 1), 4.0 * 3.0 / l0);
  EXPECT_DOUBLE_EQ(k(1, 2), 2.0 * 3.0 / l0);
  EXPECT_DOUBLE_EQ(k(2, 2), 4.0 * 3.0 / l0);
  EXPECT_EQ(k(0, 1), 0.0);
}

TEST(ForceLaw, TimoshenkoIsEquation4WithSquaredLength) {
  // q = 12 EI / (G A_s l0²) = 12 Ψ / l0² (the text's Eq. 5 lacks the square).
  const double EI = 2.0, Psi = 0.01, l0 = 0.5, q = 12.0 * Psi / (l0 * l0);
  const auto k = basic_stiffness({.EA = 1.0, .EI = EI, .shear_flexibility = Psi}, l0);
  EXPECT_NEAR(k(1, 1), EI / (l0 * (1 + q)) * (4 + q), 1e-12);
  EXPECT_NEAR(k(1, 2), EI / (l0 * (1 + q)) * (2 - q), 1e-12);
  // Pure bending (θ_i = −θ_j) does not feel shear: M = 2EI/l0 · θ for both theories.
  EXPECT_NEAR(k(1, 1) - k(1, 2), 2.0 * EI / l0, 1e-12);
}

TEST(ForceLaw, TimoshenkoCantileverTipFlexibility) {
  // A clamped–free Timoshenko element under a tip force P has v = P l³/(3EI) + P l/(G A_s).
  // From k0 in the chord frame: clamp θ_i = 0 and solve the 2×2 system for the tip (v, θ).
  const double EI = 5.0, Psi = 0.3, l = 2.0, GAs = EI / Psi;
  const auto k = basic_stiffness({.EA = 1.0, .EI = EI, .shear_flexibility = Psi}, l);
  // Transverse tip force P with zero tip moment: M_i + M_j = P l, M_j = 0 with θ_i = 0 measured
  // from the chord: θ_i' = −v/l, θ_j' = θ − v/l in chord terms.
  const double P = 1.0;
  Eigen::Matrix2d A;  // unknowns (v, θ)
  A << -(k(1, 1) + k(1, 2)) / l, k(1, 2), -(k(2, 1) + k(2, 2)) / l, k(2, 2);
  const Eigen::Vector2d rhs(-P * l, 0.0);  // M_i = −P l (moment on the element at the root)
  const Eigen::Vector2d vt = A.colPivHouseholderQr().solve(rhs);
  EXPECT_NEAR(vt[0], P * l * l * l / (3 * EI) + P * l / GAs, 1e-12);
}

// A hinged element's kept end: k_jj − k_ij²/k_ii, the propped cantilever's end stiffness —
// 3EI/l0 for Euler–Bernoulli, 12EI/(l0 (4 + q)) for Timoshenko; both ends hinged: a bar.
TEST(BeamElement, AHingeLeavesTheOtherEndAProppedCantileversStiffness) {
  const double l0 = 2.0, EI = 3.0;
  for (const double psi : {0.0, 0.05}) {
    const BasicStiffness k0 = basic_stiffness_terms({.EA = 200.0, .EI = EI, .shear_flexibility = psi}, l0);
    const double q = 12.0 * psi / (l0 * l0), kept = 12.0 * EI / (l0 * (4.0 + q));
    EXPECT_NEAR(released_stiffness(k0, true, false)(2, 2), kept, 1e-12);
    EXPECT_NEAR(released_stiffness(k0, false, true)(1, 1), kept, 1e-12);
    const Matrix3 bar = released_stiffness(k0, true, true);
    EXPECT_EQ((bar.bottomRightCorner<2, 2>().norm()), 0.0);
    EXPECT_EQ(bar(0, 0), k0.axial);
  }
}

// End springs in series with the element: with node j held, the moment at node i per radian is
// 1/(1/k + l0/4EI) (Euler–Bernoulli); no spring gives k0, an infinitely soft one the hinge.
TEST(BeamElement, AnEndSpringActsInSeriesWithTheElement) {
  const double l0 = 2.0, EI = 3.0, k = 5.0;
  const BasicStiffness k0 = basic_stiffness_terms({.EA = 200.0, .EI = EI, .shear_flexibility = 0.0}, l0);
  EXPECT_NEAR(connected_stiffness(k0, 1.0 / k, 0.0)(1, 1), 1.0 / (1.0 / k + l0 / (4.0 * EI)), 1e-12);
  EXPECT_NEAR(connected_stiffness(k0, 0.0, 1.0 / k)(2, 2), 1.0 / (1.0 / k + l0 / (4.0 * EI)), 1e-12);
  EXPECT_LE((connected_stiffness(k0, 0.0, 0.0) - k0.matrix()).norm(), 1e-12);
  EXPECT_EQ(connected_stiffness(k0, INFINITY, 0.0), released_stiffness(k0, true, false));
  // A hinge at i and a spring at j: the propped cantilever's 3EI/l0 in series with it.
  EXPECT_NEAR(connected_stiffness(k0, INFINITY, 1.0 / k)(2, 2), 1.0 / (1.0 / k + l0 / (3.0 * EI)), 1e-12);
  EXPECT_EQ(connected_stiffness(k0, 1.0 / k, 1.0 / k)(0, 0), k0.axial);
}
