// The k-point contact element in the cantilever frame (multi_point_cantilever_frame): k = 1 is
// cantilever_frame_response in every field; the whole tangent (sliding terms included) against
// central finite differences at large rotations, k = 2, 3, 5, both theories; self-equilibrium;
// at small deformations the chord frame's k-point element (the same beam, another frame).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>

#include "support/contact_trial.hpp"
#include "support/multi_point_trial.hpp"
#include "tsmframe/contact/cantilever_frame_element.hpp"
#include "tsmframe/contact/multi_point_cantilever_frame.hpp"
#include "tsmframe/contact/multi_point_element.hpp"

namespace {

using namespace tsm::contact;
using tsm::test::describe;
using tsm::test::multi_trial;
using tsm::test::MultiSpec;
using tsm::test::MultiTrial;

/// max |a − b| / ‖b‖ over the field.
double field_error(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  if (a.rows() != b.rows() || a.cols() != b.cols()) return INFINITY;
  return (a - b).cwiseAbs().maxCoeff() / std::max(b.norm(), 1e-300);
}

TEST(MultiPointCantileverFrame, OnePointIsTheCantileverFrameElementInEveryField) {
  double worst = 0.0;
  for (double psi : {0.0, 0.01})
    for (double angle : {0.0, 1.2, -2.6, 7.0})
      for (double alpha0 : {0.05, 0.3, 0.62, 0.97})
        for (bool sliding : {true, false}) {
          const tsm::test::ContactTrial t = tsm::test::contact_trial({.psi = psi, .angle = angle, .theta_i = 0.25,
                                                                      .theta_j = -0.15, .alpha0 = alpha0, .push = 1.5e-2,
                                                                      .slide = 0.01, .sliding_term = sliding,
                                                                      .cantilever_frame = true});
          const ContactResponse one = cantilever_frame_response(t.data, t.d, t.previous);
          MultiPointElementData data{.initial = t.data.initial, .section = t.data.section, .k0 = t.data.k0,
                                     .points = {{t.data.contact_start, t.data.offset}}, .edge = t.data.edge,
                                     .min_compliance = t.data.min_compliance, .sliding_term = sliding};
          const MultiPointResponse r = multi_point_cantilever_response(data, t.d, t.previous);
          SCOPED_TRACE("psi " + std::to_string(psi) + " angle " + std::to_string(angle) + " alpha " + std::to_string(alpha0));
          EXPECT_EQ(r.chord.rotation, one.chord.rotation);
          EXPECT_DOUBLE_EQ(r.alpha[0], one.alpha);
          EXPECT_DOUBLE_EQ(r.normal[0], one.normal);
          const std::pair<const char*, double> fields[] = {
              {"deformations", field_error(r.deformations, Eigen::VectorXd(one.deformations))},
              {"forces", field_error(r.forces, Eigen::VectorXd(one.forces))},
              {"nodal_forces", field_error(r.nodal_forces, Eigen::VectorXd(one.nodal_forces))},
              {"point_u", field_error(r.point_u, Eigen::VectorXd(one.point_u))},
              {"point_stiffness", field_error(r.point_stiffness, Eigen::MatrixXd::Constant(1, 1, one.point_stiffness))},
              {"tangent", field_error(r.tangent, Eigen::MatrixXd(one.tangent))},
              {"symmetric_tangent", field_error(r.symmetric_tangent, Eigen::MatrixXd(one.symmetric_tangent))},
              {"sliding_u", field_error(r.sliding_u, Eigen::VectorXd(one.sliding_u))},
              {"sliding_v", field_error(r.sliding_v, Eigen::VectorXd(one.sliding_v))}};
          for (const auto& [name, error] : fields) {
            EXPECT_LE(error, 1e-12) << name;
            worst = std::max(worst, error);
          }
        }
  std::printf("[figure] k = 1 against cantilever_frame_response: worst relative difference %.2e\n", worst);
}

class MultiPointCantileverTangent : public ::testing::TestWithParam<MultiSpec> {};

TEST_P(MultiPointCantileverTangent, MatchesFiniteDifferencesWithTheSlidingTerms) {
  MultiSpec p = GetParam();
  const MultiTrial s = multi_trial(p);
  const MultiPointResponse r = multi_point_cantilever_response(s.data, s.d, s.previous);
  for (int q = 0; q < s.data.size(); ++q) {
    ASSERT_GT(r.alpha[q], 0.0);
    ASSERT_LT(r.alpha[q], 1.0);
  }
  ASSERT_GT(r.forces.tail(s.data.size()).cwiseAbs().minCoeff(), 0.1) << "every point loaded";
  const Eigen::MatrixXd fd = tsm::test::multi_point_finite_difference_tangent(s, multi_point_cantilever_response);
  const double error = (r.tangent - fd).norm() / fd.norm();
  EXPECT_LE(error, 1e-6) << describe(p) << "\nanalytic\n" << r.tangent << "\nfd\n" << fd;
  std::printf("[figure] %s: ‖K − K_fd‖/‖K_fd‖ %.2e\n", describe(p).c_str(), error);
  // Without the sliding terms: the symmetric part, and measurably off.
  p.sliding_term = false;
  const MultiTrial without = multi_trial(p);
  const Eigen::MatrixXd Kq = multi_point_cantilever_response(without.data, without.d, without.previous).tangent;
  EXPECT_LE((Kq - Kq.transpose()).norm(), 1e-12 * Kq.norm());
  EXPECT_EQ((Kq - r.symmetric_tangent).norm(), 0.0);
  EXPECT_GT((r.tangent - Kq).norm(), 1e-4 * r.tangent.norm());
}

INSTANTIATE_TEST_SUITE_P(
    Cases, MultiPointCantileverTangent,
    ::testing::ValuesIn(tsm::test::bent_and_turned_cases()),
    tsm::test::case_name);

TEST(MultiPointCantileverFrame, ForcesAreSelfEquilibrated) {
  for (double psi : {0.0, 0.01}) {
    const MultiTrial s = multi_trial({.psi = psi, .angle = 1.3, .theta_i = 0.2, .theta_j = -0.15,
                                      .alpha0 = {0.2, 0.5, 0.75}, .push = {0.03, 0.02, 0.01}, .slide = {0.0, 0.05, 0.0}});
    tsm::test::expect_multi_point_self_equilibrated(s.data, s.d, multi_point_cantilever_response(s.data, s.d, s.previous).nodal_forces);
  }
}

TEST(MultiPointCantileverFrame, AtSmallDeformationsItIsTheChordFramesElement) {
  // The same beam and points in another frame: at D = 0 the tangents are equal (FORMULATION §2b
  // for one point), and under small pushes the forces agree to second order in the pushes.
  for (double psi : {0.0, 0.01}) {
    for (const double scale : {1e-4, 1e-5}) {
      const MultiTrial s = multi_trial({.psi = psi, .angle = 0.9, .theta_i = 0.3 * scale, .theta_j = -0.2 * scale,
                                        .alpha0 = {0.2, 0.45, 0.8}, .push = {scale, 2 * scale, -scale},
                                        .slide = {0.0, 0.0, 0.0}});
      MultiTrial straight = s;
      straight.d.head<6>().setZero();
      for (int q = 0; q < 3; ++q) straight.d.segment<2>(6 + 3 * q).setZero();
      const MultiPointResponse c0 = multi_point_cantilever_response(straight.data, straight.d, 0.0);
      const MultiPointResponse h0 = multi_point_response(straight.data, straight.d, 0.0);
      EXPECT_LE((c0.tangent - h0.tangent).norm(), 1e-12 * h0.tangent.norm()) << "psi " << psi;
      // Rotated rigidly by 0.9 and then deformed: the forces differ by O(scale²) of their size O(scale).
      const MultiPointResponse c = multi_point_cantilever_response(s.data, s.d, s.previous);
      const MultiPointResponse h = multi_point_response(s.data, s.d, s.previous);
      EXPECT_LE((c.nodal_forces - h.nodal_forces).norm(), 50.0 * scale * h.nodal_forces.norm())
          << "psi " << psi << " scale " << scale;
    }
  }
}

}  // namespace
