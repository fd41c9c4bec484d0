// The cantilever-coordinate contact element (FORMULATION §2b, issue 8): its force law against
// the matrix form, the plain cantilever as a → 0, the chord element's tangent at D = 0, the full
// tangent against central finite differences after large rigid rotations (the sliding term
// included, and shown to matter), self-equilibrium and rigid motion.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

#include "support/contact_trial.hpp"
#include "tsmframe/contact/cantilever_frame_element.hpp"
#include "tsmframe/contact/contact_response.hpp"

namespace test_cantilever_frame_element {
namespace {

using namespace tsm::contact;
using tsm::element::Matrix3;
using tsm::element::SectionStiffness;
using std::numbers::pi;

TEST(CantileverFrameLaw, SplitIsTheMatrixOfFormulation2b) {
  for (double psi : {0.0, 0.004, 0.05})
    for (double alpha : {0.02, 0.3, 0.5, 0.8, 0.995}) {
      const SectionStiffness s{.EA = 1.0, .EI = 2.5, .shear_flexibility = psi};
      const double l0 = 0.7;
      const Matrix3 k = cantilever_bending_stiffness(s, l0, alpha);
      EXPECT_LE((k - k.transpose()).norm(), 1e-12 * k.norm());
      // Schur complement of K(Y,Y): the plain cantilever, whatever α
      const Eigen::Matrix2d schur = k.topLeftCorner<2, 2>() - k.topRightCorner<2, 1>() * k.bottomLeftCorner<1, 2>() / k(2, 2);
      EXPECT_LE((schur - cantilever_stiffness(s, l0)).norm(), 1e-9 * schur.norm()) << psi << " " << alpha;
      // K(Y, v_c) is the chord element's K(Y, δy_c) (FORMULATION §2b)
      EXPECT_NEAR(k(2, 2), contact_bending_stiffness(s, l0, alpha)(2, 2), 1e-9 * k(2, 2));
    }
}

TEST(CantileverFrameLaw, TheElementAppliesThatMatrix) {
  // Horizontal element, node i at the origin and unrotated: d = (0, v_j, θ_j, v_c) is set
  // directly, and (Q, M, Y) must be §2b's matrix times it.
  for (double psi : {0.0, 0.02})
    for (double alpha : {0.25, 0.6}) {
      ContactElementData data;
      data.initial = tsm::element::initial_chord({0.0, 0.0}, {0.8, 0.0});
      data.section = {.EA = 1e3, .EI = 2.0, .shear_flexibility = psi};
      data.k0 = tsm::element::basic_stiffness(data.section, 0.8);
      data.contact_start = {alpha * 0.8, 0.0};
      data.edge = 1e-3;
      data.frame = tsm::ContactFrame::cantilever;
      const Eigen::Vector3d bend(1e-4, -3e-4, 2e-4);  // v_j, θ_j, v_c
      Vector9 d;
      d << 0, 0, 0, 0, bend[0], bend[1], 0, bend[2], 0;
      const ContactResponse r = contact_response(data, d, 0.0, false);
      const Eigen::Vector3d expected = cantilever_bending_stiffness(data.section, 0.8, alpha) * bend;
      const Eigen::Vector3d got(r.nodal_forces[4], r.nodal_forces[5], r.forces[3]);  // Q (m = y), M at j, Y
      EXPECT_LE((got - expected).norm(), 1e-9 * expected.norm()) << got.transpose() << " vs " << expected.transpose();
    }
}

TEST(CantileverFrameLaw, TendsToThePlainCantileverAsTheContactNearsTheClamp) {
  const SectionStiffness s{.EA = 1.0, .EI = 1.0, .shear_flexibility = 0.0};
  const Matrix3 k = cantilever_bending_stiffness(s, 1.0, 1e-6);
  EXPECT_NEAR(k(0, 0), 12.0, 1e-4);
  EXPECT_NEAR(k(0, 1), -6.0, 1e-4);
  EXPECT_NEAR(k(1, 1), 4.0, 1e-4);
}

using Trial = tsm::test::ContactTrial;

// The element of tests/support/contact_trial.hpp, shifted by (0.05, −0.02), its contact node
// 0.03 along the chord from α0 and turned by 0.3, in the cantilever frame or not.
Trial trial(double psi, double angle, double theta_i, double theta_j, double alpha0, double push, bool cantilever,
            bool sliding = true) {
  return tsm::test::contact_trial({.psi = psi, .angle = angle, .theta_i = theta_i, .theta_j = theta_j, .alpha0 = alpha0,
                                   .push = push, .slide = 0.03, .sliding_term = sliding, .cantilever_frame = cantilever,
                                   .shift = {0.05, -0.02}, .node_rotation = 0.3});
}

Matrix9 finite_differences(const Trial& s) { return tsm::test::finite_difference_tangent(s); }

struct Case {
  double psi, angle, theta_i, theta_j, alpha0, push;
};

class CantileverFrameTangent : public ::testing::TestWithParam<Case> {};

TEST_P(CantileverFrameTangent, MatchesFiniteDifferencesAndNeedsTheSlidingTerm) {
  const Case& p = GetParam();
  const Trial with = trial(p.psi, p.angle, p.theta_i, p.theta_j, p.alpha0, p.push, true, true);
  const Trial without = trial(p.psi, p.angle, p.theta_i, p.theta_j, p.alpha0, p.push, true, false);
  const ContactResponse r = contact_response(with.data, with.d, with.previous);
  ASSERT_GT(r.alpha, 0.0);
  ASSERT_LT(r.alpha, 1.0);
  const Matrix9 fd = finite_differences(with);
  EXPECT_LE((r.tangent - fd).norm(), 1e-6 * fd.norm()) << "analytic\n" << r.tangent << "\nfd\n" << fd;
  const Matrix9 quasi = contact_response(without.data, without.d, without.previous).tangent;
  EXPECT_GT((quasi - fd).norm(), 1e-2 * fd.norm());  // far off without the sliding term
}

INSTANTIATE_TEST_SUITE_P(Cases, CantileverFrameTangent,
                         ::testing::Values(Case{0.0, 0.0, 0.02, -0.03, 0.3, 0.02},
                                           Case{0.0, 2.5, 0.2, -0.1, 0.6, 0.03},
                                           Case{0.0, -3.0 * pi + 0.4, -0.3, 0.25, 0.2, -0.02},
                                           Case{0.01, 4.0, 0.3, 0.1, 0.7, 0.03},
                                           Case{0.002, -1.0, 0.1, -0.2, 0.85, 0.01}));

TEST(CantileverFrameElement, EqualsTheChordElementInTheUndeformedState) {
  for (double psi : {0.0, 0.01}) {
    Trial a = trial(psi, 0.0, 0.0, 0.0, 0.4, 0.0, true), b = trial(psi, 0.0, 0.0, 0.0, 0.4, 0.0, false);
    a.d.setZero();
    b.d.setZero();
    a.previous = b.previous = 0.0;
    const Matrix9 Ka = contact_response(a.data, a.d, 0.0).tangent, Kb = contact_response(b.data, b.d, 0.0).tangent;
    EXPECT_LE((Ka - Kb).norm(), 1e-9 * Kb.norm()) << "cantilever\n" << Ka << "\nchord\n" << Kb;
  }
}

TEST(CantileverFrameElement, SelfEquilibratedAndForceFreeUnderRigidMotion) {
  for (double psi : {0.0, 0.01}) {
    const Trial s = trial(psi, 1.3, 0.2, -0.15, 0.4, 0.03, true);
    const ContactResponse r = contact_response(s.data, s.d, s.previous);
    ASSERT_GT(std::abs(r.forces[3]), 1.0);
    tsm::test::expect_self_equilibrated(s.data, s.d, r.nodal_forces);
    for (double angle : {0.7, -2.9, 5.0 * pi}) {
      Trial rigid = trial(psi, angle, 0.0, 0.0, 0.35, 0.0, true);
      const Eigen::Rotation2Dd R(angle);
      const Eigen::Vector2d chord = rigid.data.initial.end - rigid.data.initial.start, shift(0.4, -0.3);
      rigid.d << shift.x(), shift.y(), angle, 0, 0, angle, 0, 0, 0;
      rigid.d.segment<2>(3) = rigid.data.initial.start + shift + R * chord - rigid.data.initial.end;
      rigid.d.segment<2>(6) = rigid.data.initial.start + shift + 0.35 * (R * chord) - rigid.data.contact_start;
      EXPECT_LT(contact_response(rigid.data, rigid.d, angle).nodal_forces.norm(), 1e-9 * 400.0) << angle;
    }
  }
}

}  // namespace

}  // namespace test_cantilever_frame_element
