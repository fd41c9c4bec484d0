// The contact law with k interior points (docs/contact-k-points.md, multi_point_law): k = 1 is
// point_load_law and connected_law; C against the textbook clamped–clamped and simply supported
// influence functions and against the Schur complement of the beam subdivided at the points; C
// symmetric positive definite; its α-derivatives against central differences; the pair floor
// between points approaching each other.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include "support/end_connections.hpp"
#include "tsmframe/contact/contact_force_law.hpp"
#include "tsmframe/contact/multi_point_law.hpp"
#include "tsmframe/element/force_law.hpp"

namespace test_multi_point_law {
namespace {

using namespace tsm::contact;
using tsm::element::SectionStiffness;
using tsm::test::connections;
using tsm::test::Ends;

constexpr double tiny_edge = 1e-9;  // a floor far below any compliance these tests reach

Eigen::VectorXd positions(std::initializer_list<double> alpha) {
  Eigen::VectorXd v(static_cast<Eigen::Index>(alpha.size()));
  std::copy(alpha.begin(), alpha.end(), v.data());
  return v;
}

Eigen::Matrix2d plain_block(const SectionStiffness& s, double l0) {
  return tsm::element::basic_stiffness(s, l0).bottomRightCorner<2, 2>();
}

/// Textbook (Roark) deflection at x of a clamped–clamped Euler–Bernoulli beam under a unit load at
/// a: b² x² (3aL − (3a + b)x) / (6EIL³) for x ≤ a, and the mirror image for x > a.
double clamped_eb(double EI, double L, double x, double a) {
  if (x > a) return clamped_eb(EI, L, L - x, L - a);
  const double b = L - a;
  return b * b * x * x * (3.0 * a * L - (3.0 * a + b) * x) / (6.0 * EI * L * L * L);
}

/// Textbook simply supported beam, unit load at a, deflection at x ≤ a: EB b x (L² − b² − x²)/(6EIL)
/// plus the shear deflection x b / (L G A_s) = Ψ x b / (EI L); mirrored for x > a.
double simply_supported(const SectionStiffness& s, double L, double x, double a) {
  if (x > a) return simply_supported(s, L, L - x, L - a);
  const double b = L - a;
  return (b * x * (L * L - b * b - x * x) / 6.0 + s.shear_flexibility * x * b) / (s.EI * L);
}

TEST(MultiPointLaw, OnePointIsPointLoadLaw) {
  for (double psi : {0.0, 0.01})
    for (double alpha : {-0.1, 0.0, 0.003, 0.3, 0.5, 0.97, 1.0, 1.2})
      for (double cap : {0.0, 1e-5}) {
        const SectionStiffness s{.EA = 1.0, .EI = 2.5, .shear_flexibility = psi};
        const PointLoadLaw one = point_load_law(s, 0.7, alpha, 1e-2, cap);
        const MultiPointLaw k = multi_point_law(s, 0.7, positions({alpha}), 1e-2, cap);
        ASSERT_EQ(k.size(), 1);
        EXPECT_EQ(k.h(0, 0), one.h_i);
        EXPECT_EQ(k.h(1, 0), one.h_j);
        EXPECT_EQ(k.dh(0, 0), one.dh_i);
        EXPECT_EQ(k.dh(1, 0), one.dh_j);
        EXPECT_EQ(k.compliance(0, 0), one.compliance);
        EXPECT_EQ(k.dcompliance.rows(0, 0), one.dcompliance);
      }
}

TEST(MultiPointLaw, OnePointConnectedIsConnectedLaw) {
  for (double psi : {0.0, 0.01})
    for (double alpha : {0.15, 0.5, 0.8})
      for (const Ends f : connections) {
        const SectionStiffness s{.EA = 1.0, .EI = 2.5, .shear_flexibility = psi};
        const ConnectedLaw one = connected_law(point_load_law(s, 0.7, alpha, 1e-3), plain_block(s, 0.7), f.i, f.j);
        const ConnectedMultiPointLaw k =
            connected_multi_point_law(multi_point_law(s, 0.7, positions({alpha}), 1e-3), plain_block(s, 0.7), f.i, f.j);
        auto near = [](double a, double b) { return std::abs(a - b) <= 1e-12 * std::max(std::abs(b), 1e-300) + 1e-300; };
        EXPECT_TRUE(near(k.law.h(0, 0), one.law.h_i)) << k.law.h(0, 0) << " " << one.law.h_i;
        EXPECT_TRUE(near(k.law.h(1, 0), one.law.h_j));
        EXPECT_TRUE(near(k.law.dh(0, 0), one.law.dh_i));
        EXPECT_TRUE(near(k.law.dh(1, 0), one.law.dh_j));
        EXPECT_TRUE(near(k.law.compliance(0, 0), one.law.compliance));
        EXPECT_TRUE(near(k.law.dcompliance.rows(0, 0), one.law.dcompliance));
        EXPECT_LE((k.k_plain - one.k_plain).norm(), 1e-12 * one.k_plain.norm() + 1e-300);
      }
}

TEST(MultiPointLaw, ClampedInfluenceIsTheTextbookBeamsAndItsDiagonalIsTodaysCompliance) {
  const double L = 0.8;
  const SectionStiffness eb{.EA = 1.0, .EI = 1.9, .shear_flexibility = 0.0};
  for (double x : {0.01, 0.2, 0.4, 0.63, 0.79})
    for (double a : {0.05, 0.3, 0.4, 0.7}) {
      const double expected = clamped_eb(eb.EI, L, x, a);
      EXPECT_NEAR(clamped_influence(eb, L, x, a), expected, 1e-13 * expected) << x << " " << a;
      EXPECT_EQ(clamped_influence(eb, L, x, a), clamped_influence(eb, L, a, x));
    }
  for (double psi : {0.0, 0.003, 0.05})
    for (double alpha : {1e-4, 0.2, 0.5, 0.9}) {
      const SectionStiffness s{.EA = 1.0, .EI = 1.9, .shear_flexibility = psi};
      const double c = point_load_law(s, L, alpha, tiny_edge).compliance;
      EXPECT_NEAR(clamped_influence(s, L, alpha * L, alpha * L), c, 1e-13 * c) << psi << " " << alpha;
    }
}

TEST(MultiPointLaw, BothEndsHingedIsASimplySupportedBeamUnderKPointLoads) {
  // A simply supported beam pressed by k rigid points: the law's C with both ends hinged is the
  // textbook flexibility of k point loads (EB, and Timoshenko's shear deflection added).
  const double L = 1.1;
  for (double psi : {0.0, 0.004, 0.03})
    for (const Eigen::VectorXd& alpha : {positions({0.2, 0.55, 0.8}), positions({0.1, 0.3, 0.45, 0.6, 0.93})}) {
      const SectionStiffness s{.EA = 1.0, .EI = 0.7, .shear_flexibility = psi};
      const ConnectedMultiPointLaw c = connected_multi_point_law(multi_point_law(s, L, alpha, tiny_edge),
                                                                 plain_block(s, L), INFINITY, INFINITY);
      for (int p = 0; p < alpha.size(); ++p)
        for (int q = 0; q < alpha.size(); ++q) {
          const double expected = simply_supported(s, L, alpha[p] * L, alpha[q] * L);
          EXPECT_NEAR(c.law.compliance(p, q), expected, 1e-12 * expected) << psi << " " << p << " " << q;
        }
      EXPECT_EQ(c.law.h.norm(), 0.0);
      EXPECT_EQ(c.k_plain.norm(), 0.0);
    }
}

/// The beam subdivided at the points (sorted) into k + 1 two-node elements of the textbook
/// Timoshenko stiffness (exact for nodal loads), both end deflections held, the interior rotations
/// condensed out: the stiffness (θ_i, θ_j, w_1 … w_k) → (M_i, M_j, Y_1 … Y_k), K3's matrix.
Eigen::MatrixXd subdivided_beam(const SectionStiffness& s, double L, const Eigen::VectorXd& alpha) {
  const int k = static_cast<int>(alpha.size());
  // Global dofs: 0 θ_i, 1 θ_j, 2 … k+1 w_p, k+2 … 2k+1 φ_p; node n = 0 … k+1 along the beam.
  auto w_dof = [&](int n) { return (n == 0 || n == k + 1) ? -1 : 1 + n; };
  auto phi_dof = [&](int n) { return n == 0 ? 0 : n == k + 1 ? 1 : k + 1 + n; };
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(2 * k + 2, 2 * k + 2);
  for (int e = 0; e <= k; ++e) {
    const double x0 = e == 0 ? 0.0 : alpha[e - 1] * L, x1 = e == k ? L : alpha[e] * L, l = x1 - x0;
    const double q = 12.0 * s.shear_flexibility / (l * l), f = s.EI / (l * l * l * (1.0 + q));
    Eigen::Matrix4d ke;
    ke << 12, 6 * l, -12, 6 * l, 6 * l, (4 + q) * l * l, -6 * l, (2 - q) * l * l, -12, -6 * l, 12, -6 * l, 6 * l,
        (2 - q) * l * l, -6 * l, (4 + q) * l * l;
    ke *= f;
    const int dofs[4] = {w_dof(e), phi_dof(e), w_dof(e + 1), phi_dof(e + 1)};
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        if (dofs[a] >= 0 && dofs[b] >= 0) K(dofs[a], dofs[b]) += ke(a, b);
  }
  const int n = k + 2;
  const Eigen::MatrixXd Kaa = K.topLeftCorner(n, n), Kab = K.topRightCorner(n, k), Kbb = K.bottomRightCorner(k, k);
  return Kaa - Kab * Kbb.lu().solve(Kab.transpose());
}

TEST(MultiPointLaw, IsTheSchurComplementOfTheBeamSubdividedAtThePoints) {
  const double L = 0.9;
  for (double psi : {0.0, 0.002, 0.02}) {
    const SectionStiffness s{.EA = 1.0, .EI = 1.3, .shear_flexibility = psi};
    const Eigen::VectorXd alpha = positions({0.15, 0.5, 0.72});
    const MultiPointLaw law = multi_point_law(s, L, alpha, tiny_edge);
    const Eigen::MatrixXd reference = subdivided_beam(s, L, alpha);
    // C and H from the subdivided beam: C = (K_ww)⁻¹, H = K_θw C.
    const Eigen::MatrixXd C = reference.bottomRightCorner(3, 3).inverse();
    const Eigen::MatrixXd H = reference.topRightCorner(2, 3) * C;
    EXPECT_LE((law.compliance - C).norm(), 1e-11 * C.norm()) << "psi " << psi << "\n" << law.compliance << "\n" << C;
    std::printf("subdivided beam, psi %g: C off by %.2e, H by %.2e (relative)\n", psi, (law.compliance - C).norm() / C.norm(),
                (law.h - H).norm() / H.norm());
    EXPECT_LE((law.h - H).norm(), 1e-11 * H.norm()) << "psi " << psi;
    // The whole of K3 as well: K_θθ = k_plain + H C⁻¹ Hᵀ.
    const Eigen::MatrixXd Cinv = law.compliance.inverse();
    const Eigen::Matrix2d Ktt = plain_block(s, L) + law.h * Cinv * law.h.transpose();
    EXPECT_LE((Ktt - reference.topLeftCorner(2, 2)).norm(), 1e-10 * Ktt.norm()) << "psi " << psi;
  }
}

TEST(MultiPointLaw, ComplianceIsSymmetricPositiveDefiniteAwayFromCoincidentPoints) {
  for (double psi : {0.0, 0.01})
    for (const Eigen::VectorXd& alpha :
         {positions({0.3, 0.6}), positions({0.9, 0.1, 0.5}), positions({0.02, 0.2, 0.41, 0.77, 0.985})}) {
      const SectionStiffness s{.EA = 1.0, .EI = 1.3, .shear_flexibility = psi};
      const MultiPointLaw law = multi_point_law(s, 0.6, alpha, 1e-2);
      EXPECT_EQ((law.compliance - law.compliance.transpose()).norm(), 0.0);
      const Eigen::VectorXd lambda = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(law.compliance).eigenvalues();
      EXPECT_GT(lambda.minCoeff(), 1e-6 * lambda.maxCoeff()) << lambda.transpose();
      for (const Ends f : connections) {
        const MultiPointLaw c = connected_multi_point_law(law, plain_block(s, 0.6), f.i, f.j).law;
        EXPECT_LE((c.compliance - c.compliance.transpose()).norm(), 1e-15 * c.compliance.norm());
        EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(c.compliance).eigenvalues().minCoeff(), 0.0);
      }
    }
}

/// ∂H/∂α_p, ∂C/∂α_p and ∂(M, Y)/∂α_p against central differences (step 1e-6).
void expect_derivatives_match(const SectionStiffness& s, double l0, const Eigen::VectorXd& alpha, double edge,
                              const Ends& f, const std::string& what) {
  const Eigen::Matrix2d kp = plain_block(s, l0);
  auto law_at = [&](const Eigen::VectorXd& a) {
    return connected_multi_point_law(multi_point_law(s, l0, a, edge), kp, f.i, f.j);
  };
  const ConnectedMultiPointLaw at = law_at(alpha);
  const Eigen::Vector2d theta(0.03, -0.05);
  Eigen::VectorXd deflections(alpha.size());
  for (int p = 0; p < alpha.size(); ++p) deflections[p] = 1e-3 * (1.0 + 0.3 * p);
  const MultiPointForces forces = multi_point_forces(at.law, at.k_plain, theta, deflections);
  const double step = 1e-6;
  for (int p = 0; p < alpha.size(); ++p) {
    Eigen::VectorXd up = alpha, down = alpha;
    up[p] += step;
    down[p] -= step;
    const ConnectedMultiPointLaw u = law_at(up), d = law_at(down);
    const Eigen::Matrix2Xd dH = (u.law.h - d.law.h) / (2 * step);
    Eigen::Matrix2Xd expected_dH = Eigen::Matrix2Xd::Zero(2, alpha.size());
    expected_dH.col(p) = at.law.dh.col(p);
    EXPECT_LE((dH - expected_dH).norm(), 1e-7 * (expected_dH.norm() + at.law.h.norm())) << what << " p " << p;
    const Eigen::MatrixXd dC = (u.law.compliance - d.law.compliance) / (2 * step);
    EXPECT_LE((dC - at.law.dcompliance.dense(p)).norm(), 1e-6 * dC.norm() + 1e-9 * at.law.compliance.norm())
        << what << " p " << p << "\nanalytic\n" << at.law.dcompliance.dense(p) << "\nfd\n" << dC;
    const MultiPointForces fu = multi_point_forces(u.law, u.k_plain, theta, deflections),
                           fd = multi_point_forces(d.law, d.k_plain, theta, deflections);
    const Eigen::VectorXd dY = (fu.point_forces - fd.point_forces) / (2 * step);
    const Eigen::Vector2d dM = (fu.moments - fd.moments) / (2 * step);
    EXPECT_LE((dY - forces.dpoint_forces.col(p)).norm(), 1e-6 * (dY.norm() + forces.point_forces.norm())) << what << " p " << p;
    EXPECT_LE((dM - forces.dmoments.col(p)).norm(), 1e-6 * (dM.norm() + forces.moments.norm())) << what << " p " << p;
  }
}

TEST(MultiPointLaw, DerivativesInAlphaMatchFiniteDifferences) {
  for (double psi : {0.0, 0.02})
    for (const Eigen::VectorXd& alpha :
         {positions({0.25, 0.6}), positions({0.7, 0.1, 0.45}), positions({0.05, 0.2, 0.41, 0.77, 0.9})}) {
      const SectionStiffness s{.EA = 1.0, .EI = 1.7, .shear_flexibility = psi};
      expect_derivatives_match(s, 0.6, alpha, 1e-3, {0.0, 0.0}, "rigid psi " + std::to_string(psi));
      for (const Ends f : connections)
        expect_derivatives_match(s, 0.6, alpha, 1e-3, f, "ends " + std::to_string(f.i) + " " + std::to_string(f.j));
    }
}

TEST(MultiPointLaw, NoPointsIsThePlainElement) {
  const SectionStiffness s{.EA = 1.0, .EI = 1.7, .shear_flexibility = 0.01};
  const MultiPointLaw law = multi_point_law(s, 0.6, Eigen::VectorXd(0), 1e-3);
  EXPECT_EQ(law.size(), 0);
  const Eigen::Vector2d theta(0.02, -0.01);
  const MultiPointForces f = multi_point_forces(law, plain_block(s, 0.6), theta, Eigen::VectorXd(0));
  EXPECT_EQ(f.moments, plain_block(s, 0.6) * theta);
  EXPECT_EQ(f.point_forces.size(), 0);
}

// ---- Two points approaching each other (the pair floor, K11) ----

TEST(MultiPointLaw, APairCloserThanTheEdgeHasTheFloorsDifferenceCompliance) {
  const double l0 = 0.5, edge = 1e-2;
  for (double psi : {0.0, 1e-6}) {
    const SectionStiffness s{.EA = 1.0, .EI = 2.0, .shear_flexibility = psi};
    const double floor = compliance_floor(s, l0, edge, 0.0);
    EXPECT_EQ(floor, point_load_law(s, l0, 0.0, edge).compliance) << "the edge's floor";
    for (double gap : {0.0, 1e-6, 1e-4, 2e-3}) {
      const Eigen::VectorXd alpha = positions({0.4, 0.4 + gap});
      const MultiPointLaw raw = multi_point_law(s, l0, alpha, tiny_edge), law = multi_point_law(s, l0, alpha, edge);
      const Eigen::Vector2d diff(1.0, -1.0), common(1.0, 1.0);
      ASSERT_LT(diff.dot(raw.compliance * diff), floor) << "the pair floor binds at gap " << gap;
      // To rounding in C's entries: the floor is ~1e-4 of them here, d' a difference of them.
      EXPECT_NEAR(diff.dot(law.compliance * diff), floor, 1e-14 * law.compliance.norm()) << gap;
      EXPECT_LE((law.compliance * common - raw.compliance * common).norm(), 1e-15 * raw.compliance.norm()) << gap;
      const Eigen::VectorXd lambda = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(law.compliance).eigenvalues();
      EXPECT_GT(lambda.minCoeff(), 0.4 * floor) << gap;
    }
    // Farther apart than about the edge the law is untouched.
    const Eigen::VectorXd apart = positions({0.4, 0.45});
    EXPECT_EQ(multi_point_law(s, l0, apart, edge).compliance, multi_point_law(s, l0, apart, tiny_edge).compliance);
  }
}

TEST(MultiPointLaw, CoincidentPointsShareTheOnePointForceEvenly) {
  // Two points at one place pushed to one deflection carry what one point would, half each (to
  // C's conditioning, ~C_pp / c_floor ≈ 1e4 here); as they come together the forces approach that
  // split continuously — linearly in the gap once the pair floor binds (a Timoshenko beam's shear
  // keeps a finite force pair between close points until then).
  for (double psi : {0.0, 0.01}) {
    const SectionStiffness s{.EA = 1.0, .EI = 2.0, .shear_flexibility = psi};
    const double l0 = 0.5, edge = 1e-2, alpha = 0.37;
    const Eigen::Matrix2d kp = plain_block(s, l0);
    const Eigen::Vector2d theta(0.02, -0.03);
    const MultiPointForces one = multi_point_forces(multi_point_law(s, l0, positions({alpha}), edge), kp, theta,
                                                    positions({1e-3}));
    const MultiPointForces two = multi_point_forces(multi_point_law(s, l0, positions({alpha, alpha}), edge), kp, theta,
                                                    positions({1e-3, 1e-3}));
    EXPECT_NEAR(two.point_forces[0], 0.5 * one.point_forces[0], 1e-10 * std::abs(one.point_forces[0]));
    EXPECT_NEAR(two.point_forces[1], 0.5 * one.point_forces[0], 1e-10 * std::abs(one.point_forces[0]));
    EXPECT_LE((two.moments - one.moments).norm(), 1e-10 * one.moments.norm());
    double previous = INFINITY;
    for (double gap : {1e-6, 1e-7, 1e-8, 1e-9}) {
      const Eigen::VectorXd at = positions({alpha, alpha + gap});
      const MultiPointForces near =
          multi_point_forces(multi_point_law(s, l0, at, edge), kp, theta, positions({1e-3, 1e-3}));
      const double off = (near.point_forces - two.point_forces).norm();
      EXPECT_LT(off, previous) << gap;
      previous = off;
    }
    EXPECT_LT(previous, 1e-4 * std::abs(one.point_forces[0]));
  }
}

TEST(MultiPointLaw, PairFloorDerivativesMatchFiniteDifferences) {
  for (double psi : {0.0, 1e-5}) {
    const SectionStiffness s{.EA = 1.0, .EI = 1.7, .shear_flexibility = psi};
    const Eigen::VectorXd alpha = positions({0.4, 0.402, 0.7});
    const MultiPointLaw raw = multi_point_law(s, 0.6, alpha, tiny_edge);
    const double d = raw.compliance(0, 0) + raw.compliance(1, 1) - 2 * raw.compliance(0, 1);
    ASSERT_LT(d, compliance_floor(s, 0.6, 1e-2, 0.0)) << "the pair floor binds";
    expect_derivatives_match(s, 0.6, alpha, 1e-2, {0.0, 0.0}, "pair floor");
    expect_derivatives_match(s, 0.6, alpha, 1e-2, {INFINITY, 0.3}, "pair floor, hinge and spring");
  }
}

}  // namespace

}  // namespace test_multi_point_law
