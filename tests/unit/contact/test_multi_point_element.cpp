// The contact element with k interior points (docs/contact-k-points.md §7, multi_point_element):
// k = 1 is chord_frame_response in every field; the whole tangent (sliding terms included)
// against central finite differences at large chord rotations, k = 2, 3, 5, both theories, rigid,
// hinged and sprung ends; self-equilibrium and rigid motion; a beam pressed by k rigid points
// against the textbook beam under k point loads.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include "support/contact_trial.hpp"
#include "support/end_connections.hpp"
#include "support/multi_point_trial.hpp"
#include "tsmframe/contact/contact_element.hpp"
#include "tsmframe/contact/multi_point_element.hpp"

namespace test_multi_point_element {
namespace {

using namespace tsm::contact;
using tsm::test::connections;
using tsm::test::Ends;

using tsm::test::describe;
using tsm::test::multi_trial;
using tsm::test::MultiSpec;
using tsm::test::MultiTrial;

Eigen::MatrixXd finite_difference_tangent(const MultiTrial& s) {
  return tsm::test::multi_point_finite_difference_tangent(s, multi_point_response);
}

// ---- k = 1 is today's element ----

/// |a − b| ≤ 1e-12 ‖b‖ (the whole field's scale), entry by entry.
template <class A, class B>
void expect_field(const A& a, const B& b, const char* name, double& worst) {
  ASSERT_EQ(a.rows(), b.rows()) << name;
  ASSERT_EQ(a.cols(), b.cols()) << name;
  const double scale = std::max(Eigen::MatrixXd(b).norm(), 1e-300);
  const double error = (Eigen::MatrixXd(a) - Eigen::MatrixXd(b)).cwiseAbs().maxCoeff() / scale;
  worst = std::max(worst, error);
  EXPECT_LE(error, 1e-12) << name << "\n" << a << "\nexpected\n" << b;
}

TEST(MultiPointElement, OnePointIsTodaysContactElementInEveryField) {
  double worst = 0.0;
  for (double psi : {0.0, 0.01})
    for (double angle : {0.0, 1.2, -2.6, 7.0})
      for (double alpha0 : {0.05, 0.3, 0.62, 0.97})
        for (const Ends f : {Ends{0.0, 0.0}, connections[0], connections[1], connections[2], connections[4], connections[5]})
          for (bool sliding : {true, false}) {
            tsm::test::ContactTrial t = tsm::test::contact_trial(
                {.psi = psi, .angle = angle, .theta_i = 0.25, .theta_j = -0.15, .alpha0 = alpha0, .push = 1.5e-2,
                 .slide = 0.01, .sliding_term = sliding});
            t.data.flexibility_i = f.i;
            t.data.flexibility_j = f.j;
            const ContactResponse today = chord_frame_response(t.data, t.d, t.previous);
            MultiPointElementData data{.initial = t.data.initial, .section = t.data.section, .k0 = t.data.k0,
                                       .points = {{t.data.contact_start, t.data.offset}}, .edge = t.data.edge,
                                       .min_compliance = t.data.min_compliance, .sliding_term = sliding,
                                       .flexibility_i = f.i, .flexibility_j = f.j};
            const MultiPointResponse r = multi_point_response(data, t.d, t.previous);
            SCOPED_TRACE("psi " + std::to_string(psi) + " angle " + std::to_string(angle) + " alpha " +
                         std::to_string(alpha0) + " ends " + std::to_string(f.i) + " " + std::to_string(f.j));
            EXPECT_EQ(r.chord.rotation, today.chord.rotation);
            EXPECT_EQ(r.chord.length, today.chord.length);
            EXPECT_EQ(r.alpha[0], today.alpha);
            EXPECT_EQ(r.normal[0], today.normal);
            EXPECT_EQ(r.deformations, Eigen::VectorXd(today.deformations));
            expect_field(r.forces, today.forces, "forces", worst);
            expect_field(r.nodal_forces, today.nodal_forces, "nodal_forces", worst);
            expect_field(r.point_u, today.point_u, "point_u", worst);
            expect_field(r.point_stiffness, Eigen::Matrix<double, 1, 1>(today.point_stiffness), "point_stiffness", worst);
            expect_field(r.tangent, today.tangent, "tangent", worst);
            expect_field(r.symmetric_tangent, today.symmetric_tangent, "symmetric_tangent", worst);
            expect_field(r.sliding_u, today.sliding_u, "sliding_u", worst);
            expect_field(r.sliding_v, today.sliding_v, "sliding_v", worst);
          }
  std::printf("k = 1 against chord_frame_response: worst relative difference %.2e\n", worst);
}

// ---- The whole tangent against finite differences ----

class MultiPointTangent : public ::testing::TestWithParam<MultiSpec> {};

TEST_P(MultiPointTangent, MatchesFiniteDifferencesWithTheSlidingTerms) {
  double worst = 0.0;
  for (const Ends f : {Ends{0.0, 0.0}, connections[0], connections[2], connections[4], connections[5]}) {
    MultiSpec p = GetParam();
    p.ends = f;
    const MultiTrial s = multi_trial(p);
    const MultiPointResponse r = multi_point_response(s.data, s.d, s.previous);
    for (int q = 0; q < s.data.size(); ++q) {
      ASSERT_GT(r.alpha[q], 0.0);
      ASSERT_LT(r.alpha[q], 1.0);
    }
    ASSERT_GT(r.forces.tail(s.data.size()).cwiseAbs().minCoeff(), 0.1) << "every point loaded";
    const Eigen::MatrixXd fd = finite_difference_tangent(s);
    EXPECT_LE((r.tangent - fd).norm(), 1e-6 * fd.norm()) << describe(p) << "\nanalytic\n" << r.tangent << "\nfd\n" << fd;
    worst = std::max(worst, (r.tangent - fd).norm() / fd.norm());
    // Without the sliding terms: symmetric, and measurably off.
    p.sliding_term = false;
    const MultiTrial without = multi_trial(p);
    const Eigen::MatrixXd Kq = multi_point_response(without.data, without.d, without.previous).tangent;
    EXPECT_LE((Kq - Kq.transpose()).norm(), 1e-12 * Kq.norm()) << describe(p);
    EXPECT_EQ((Kq - r.symmetric_tangent).norm(), 0.0) << describe(p);
    EXPECT_GT((r.tangent - Kq).norm(), 1e-4 * r.tangent.norm()) << describe(p);
  }
  std::printf("tangent against central differences: worst ‖K − K_fd‖/‖K_fd‖ %.2e\n", worst);
}

INSTANTIATE_TEST_SUITE_P(
    Cases, MultiPointTangent,
    ::testing::ValuesIn(tsm::test::bent_and_turned_cases()),
    tsm::test::case_name);

TEST(MultiPointElement, TangentWithAPairOnTheFloorMatchesFiniteDifferences) {
  for (double psi : {0.0, 1e-6}) {
    MultiSpec p{.psi = psi, .angle = 1.3, .theta_i = 0.2, .theta_j = -0.1, .alpha0 = {0.4, 0.4005, 0.7},
                .push = {2e-2, 2.1e-2, 1e-2}, .slide = {0.0, 0.0, 0.0}};
    MultiTrial s = multi_trial(p);
    s.data.edge = 1e-2;
    const MultiPointResponse r = multi_point_response(s.data, s.d, s.previous);
    const Eigen::MatrixXd fd = finite_difference_tangent(s);
    EXPECT_LE((r.tangent - fd).norm(), 1e-6 * fd.norm()) << "psi " << psi;
  }
}

TEST(MultiPointElement, NoPointsIsThePlainElement) {
  for (double psi : {0.0, 0.01}) {
    const MultiTrial s = multi_trial({.psi = psi, .angle = 1.6, .theta_i = 0.2, .theta_j = -0.3});
    const MultiPointResponse r = multi_point_response(s.data, s.d, s.previous);
    ASSERT_EQ(r.nodal_forces.size(), 6);
    const Eigen::Vector3d S = s.data.k0 * r.deformations;  // Eq. 3 / 4
    EXPECT_LE((r.forces - S).norm(), 1e-14 * S.norm());
    EXPECT_LE((r.nodal_forces - tsm::element::equilibrium_matrix(r.chord) * S).norm(), 1e-14 * S.norm());
    const Eigen::MatrixXd fd = finite_difference_tangent(s);
    EXPECT_LE((r.tangent - fd).norm(), 1e-6 * fd.norm());
  }
}

// ---- Statics ----

TEST(MultiPointElement, ForcesAreSelfEquilibratedAndRigidMotionMakesNone) {
  for (double psi : {0.0, 0.01}) {
    const MultiTrial s = multi_trial({.psi = psi, .angle = 1.3, .theta_i = 0.2, .theta_j = -0.15,
                                      .alpha0 = {0.2, 0.5, 0.75}, .push = {0.03, 0.02, 0.01}, .slide = {0.0, 0.05, 0.0}});
    const MultiPointResponse r = multi_point_response(s.data, s.d, s.previous);
    const Eigen::VectorXd& F = r.nodal_forces;
    tsm::test::expect_multi_point_self_equilibrated(s.data, s.d, F);
    // Y_p acts as Y_p · point_u.col(p), the rest is the plain element's.
    const Eigen::VectorXd plain = multi_point_equilibrium_matrix(r.chord, r.alpha) *
                                  (Eigen::VectorXd(6) << r.forces[0], s.data.k0.bottomRightCorner<2, 2>() *
                                                                          r.deformations.segment<2>(1), 0, 0, 0).finished();
    EXPECT_LE((plain + r.point_u * r.forces.tail(3) - F).norm(), 1e-12 * F.norm());
  }
  for (double angle : {0.0, 0.7, -2.9}) {  // rigid motion: no force
    MultiTrial s = multi_trial({.psi = 0.01, .angle = angle, .alpha0 = {0.2, 0.5, 0.75}, .push = {0, 0, 0}, .slide = {0, 0, 0}});
    const Eigen::Rotation2Dd R(angle);
    const Eigen::Vector2d shift(0.4, -0.3), chord = s.data.initial.end - s.data.initial.start;
    s.d.segment<2>(0) = shift;
    s.d.segment<2>(3) = s.data.initial.start + shift + R * chord - s.data.initial.end;
    for (int q = 0; q < 3; ++q)
      s.d.segment<2>(6 + 3 * q) = s.data.initial.start + shift + R * (s.data.points[q].start - s.data.initial.start) -
                                  s.data.points[q].start;
    const MultiPointResponse r = multi_point_response(s.data, s.d, s.previous);
    EXPECT_LT(r.nodal_forces.norm(), 1e-9 * 400.0) << angle;
  }
}

/// Textbook simply supported beam (as in test_multi_point_law.cpp): unit load at a, deflection at x.
double simply_supported(const tsm::element::SectionStiffness& s, double L, double x, double a) {
  if (x > a) return simply_supported(s, L, L - x, L - a);
  const double b = L - a;
  return (b * x * (L * L - b * b - x * x) / 6.0 + s.shear_flexibility * x * b) / (s.EI * L);
}

TEST(MultiPointElement, ASimplySupportedBeamPressedByKRigidPointsCarriesTheTextbookLoads) {
  // Both ends hinged to nodes that stay put (the chord turned by 0.9 rad), k contact nodes placed
  // where the textbook beam under loads P would deflect them: the element's Y are those P.
  for (double psi : {0.0, 0.01})
    for (const std::vector<double>& alpha0 : {std::vector<double>{0.3, 0.6}, std::vector<double>{0.1, 0.3, 0.45, 0.7, 0.9}}) {
      const int k = static_cast<int>(alpha0.size());
      MultiTrial s = multi_trial({.psi = psi, .angle = 0.9, .alpha0 = alpha0, .push = std::vector<double>(k, 0.0),
                                  .slide = std::vector<double>(k, 0.0), .ends = {INFINITY, INFINITY}});
      const double L = s.data.initial.length;
      const Eigen::Rotation2Dd R(0.9);
      const Eigen::Vector2d chord = s.data.initial.end - s.data.initial.start, e = (R * chord).normalized(),
                            n(-e.y(), e.x());
      s.d.segment<2>(3) = s.data.initial.start + R * chord - s.data.initial.end;  // no stretch
      Eigen::VectorXd P(k);
      for (int q = 0; q < k; ++q) P[q] = (q % 2 ? -1.0 : 1.5) * (1.0 + 0.1 * q);
      for (int q = 0; q < k; ++q) {
        double w = 0.0;
        for (int t = 0; t < k; ++t) w += simply_supported(s.data.section, L, alpha0[q] * L, alpha0[t] * L) * P[t];
        s.d.segment<2>(6 + 3 * q) =
            s.data.initial.start + alpha0[q] * (R * chord) + w * n - s.data.points[q].start;
      }
      const MultiPointResponse r = multi_point_response(s.data, s.d, s.previous);
      EXPECT_LE((r.forces.tail(k) - P).norm(), 1e-9 * P.norm()) << "psi " << psi << " k " << k << "\n"
                                                                 << r.forces.tail(k).transpose();
      EXPECT_EQ(r.forces[1], 0.0);
      EXPECT_EQ(r.forces[2], 0.0);
    }
}

}  // namespace

}  // namespace test_multi_point_element
