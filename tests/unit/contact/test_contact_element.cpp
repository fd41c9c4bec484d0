// The three-node contact element (FORMULATION §2): the full tangent (sliding term included)
// against central finite differences at large rigid rotations, self-equilibrium, rigid motion,
// and hinged or sprung ends. Its force law: test_contact_force_law.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

#include "support/contact_trial.hpp"
#include "support/end_connections.hpp"
#include "tsmframe/contact/contact_response.hpp"

namespace {

using namespace tsm::contact;
using tsm::test::connections;
using tsm::test::Ends;
using std::numbers::pi;

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
    tsm::test::expect_self_equilibrated(s.data, s.d, r.nodal_forces);
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
