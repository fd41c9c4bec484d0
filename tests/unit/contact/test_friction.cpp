// Coulomb friction at a one-point contact (friction.hpp, docs/friction.md F1–F14): the return map
// on and inside the cone, the tangent against central differences in stick and in slip (both
// normals, both theories, rigid, hinged and sprung ends, turned and bent), its split, the nodal
// forces self-equilibrated and blind to rigid motion, and μ = 0 leaving the element as it was.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "support/contact_trial.hpp"
#include "support/end_connections.hpp"
#include "support/multi_point_trial.hpp"
#include "tsmframe/contact/contact_response.hpp"
#include "tsmframe/contact/deflected_normal_element.hpp"
#include "tsmframe/contact/friction.hpp"
#include "tsmframe/contact/multi_point_element.hpp"

namespace {

using namespace tsm::contact;
using tsm::ContactNormal;
using tsm::test::ContactTrial;
using tsm::test::ContactTrialSpec;
using tsm::test::Ends;

constexpr double mu = 0.3;

/// The trial element with friction: the anchor put where the trial force is `share` times the
/// Coulomb bound (|share| < 1: stick, > 1: slip; its sign the slip's direction).
ContactTrial frictional(const ContactTrialSpec& spec, ContactNormal normal, Ends ends, double share) {
  ContactTrial t = tsm::test::contact_trial(spec);
  t.data.normal = normal;
  t.data.flexibility_i = ends.i;
  t.data.flexibility_j = ends.j;
  const ContactResponse plain = contact_response(t.data, t.d, t.previous, false);
  const double Y = plain.forces[3];
  FrictionData& f = t.data.friction;
  f.mu = mu;
  f.side = Y > 0.0 ? -1 : 1;  // pressing
  f.arc_start = 0.7;
  f.anchored = true;
  // The arc length of the section under the node (the foot of the bent shape's normal).
  const double l0 = t.data.initial.length, l = plain.chord.length;
  const double arc = f.arc_start + l0 * (plain.alpha + plain.normal * shape_slope_at(t.data, plain, false).w_alpha / (l * l));
  const double c_T = tangential_compliance(t.data.section.EA, l0, plain.alpha, t.data.edge, 0.0).value;
  const double slope = normal == ContactNormal::deflected ? deflected_normal(t.data, plain).slope : 0.0;
  const double D = 1.0 - f.side * (share > 0 ? 1.0 : -1.0) * mu * slope;
  f.anchor = arc - share * mu * (-f.side * Y) / D * c_T;
  return t;
}

/// No net force, no net moment (friction's column a_Z is ∂α/∂x scaled: self-equilibrated).
void expect_self_equilibrated(const ContactTrial& t, const Vector9& F) {
  const double scale = F.cwiseAbs().maxCoeff();
  EXPECT_NEAR(F[0] + F[3] + F[6], 0.0, 1e-11 * scale);
  EXPECT_NEAR(F[1] + F[4] + F[7], 0.0, 1e-11 * scale);
  const Eigen::Vector2d xi = t.data.initial.start + t.d.segment<2>(0), xj = t.data.initial.end + t.d.segment<2>(3),
                        xc = t.data.contact_start + t.d.segment<2>(6);
  const auto cross = [](const Eigen::Vector2d& x, double fx, double fy) { return x.x() * fy - x.y() * fx; };
  EXPECT_NEAR(F[2] + F[5] + F[8] + cross(xi, F[0], F[1]) + cross(xj, F[3], F[4]) + cross(xc, F[6], F[7]), 0.0, 1e-11 * scale);
}

ContactTrialSpec spec_of(double psi, double angle, double theta_i, double theta_j, double slide) {
  // Beyond the span the law's compliance is the edge floor's: a push a thousandth as deep there.
  const double push = slide < -0.4 ? 4e-6 : 0.004;
  return {.psi = psi, .angle = angle, .theta_i = theta_i, .theta_j = theta_j, .alpha0 = 0.4, .push = push, .slide = slide};
}

/// ∂(nodal forces)/∂d by central differences of step h.
Matrix9 differenced_tangent(const ContactTrial& t, double h) {
  Matrix9 K;
  for (int b = 0; b < 9; ++b) {
    Vector9 plus = t.d, minus = t.d;
    plus[b] += h;
    minus[b] -= h;
    K.col(b) = (contact_response(t.data, plus, t.previous, false).nodal_forces -
                contact_response(t.data, minus, t.previous, false).nodal_forces) / (2 * h);
  }
  return K;
}

std::string describe_friction(const ContactTrialSpec& p, ContactNormal normal, Ends ends, double share) {
  return "psi " + std::to_string(p.psi) + " angle " + std::to_string(p.angle) + " theta " + std::to_string(p.theta_i) +
         " " + std::to_string(p.theta_j) + " slide " + std::to_string(p.slide) +
         (normal == ContactNormal::deflected ? " deflected" : " chord") + " ends " + std::to_string(ends.i) + " " +
         std::to_string(ends.j) + " share " + std::to_string(share);
}

TEST(Friction, ReturnMapSticksInsideTheConeAndSlipsOnIt) {
  FrictionData f{.mu = 0.25, .side = -1, .anchored = true, .anchor = 2.0};
  const double Y = 8.0, c_T = 1e-3;  // compression 8, bound 2
  FrictionResult stick = return_map(f, Y, 0.0, 2.0015, c_T);  // trial 1.5
  EXPECT_EQ(stick.status, FrictionStatus::stick);
  EXPECT_NEAR(stick.Z, 1.5, 1e-12);
  EXPECT_EQ(stick.trial_anchor, 2.0);
  FrictionResult slip = return_map(f, Y, 0.0, 1.997, c_T);  // trial −3
  EXPECT_EQ(slip.status, FrictionStatus::slip);
  EXPECT_DOUBLE_EQ(slip.Z, -2.0);
  EXPECT_NEAR(slip.trial_anchor, 1.997 + 2e-3, 1e-15);  // the anchor follows: the spring holds μp
  // With a slope the normal force is Y − Z w' and the bound μ times its compression (F8).
  const double w = 0.1;
  FrictionResult tilted = return_map(f, Y, w, 2.004, c_T);
  EXPECT_EQ(tilted.status, FrictionStatus::slip);
  EXPECT_NEAR(std::abs(tilted.Z), f.mu * (-f.side * tilted.normal_Y), 1e-14);
  EXPECT_NEAR(tilted.tangential, tilted.Z * std::sqrt(1 + w * w), 1e-15);
  f.anchored = false;
  const FrictionResult touching = return_map(f, Y, 0.0, 2.1, c_T);  // anchored where it touches
  EXPECT_EQ(touching.status, FrictionStatus::stick);
  EXPECT_EQ(touching.Z, 0.0);
  EXPECT_EQ(touching.trial_anchor, 2.1);
  f.anchored = true;
  EXPECT_EQ(return_map(f, -Y, 0.0, 2.1, c_T).status, FrictionStatus::open);  // it would pull
}

TEST(Friction, TangentialComplianceIsTheBarsAxialFlexibilityFlooredAndCapped) {
  const double EA = 200.0, l0 = 2.0;
  const TangentialCompliance mid = tangential_compliance(EA, l0, 0.3, 0.01, 0.0);
  EXPECT_DOUBLE_EQ(mid.value, 0.3 * 0.7 * l0 / EA);
  EXPECT_DOUBLE_EQ(mid.d_alpha, 0.4 * l0 / EA);
  const TangentialCompliance near_end = tangential_compliance(EA, l0, 0.001, 0.01, 0.0);
  EXPECT_DOUBLE_EQ(near_end.value, 0.01 * 0.99 * l0 / EA);
  EXPECT_EQ(near_end.d_alpha, 0.0);
  EXPECT_EQ(tangential_compliance(EA, l0, 0.3, 0.01, 1.0).value, 1.0);  // the cap binds
}

TEST(Friction, TangentMatchesCentralDifferencesInStickAndInSlip) {
  double worst = 0.0;
  std::string where;
  const Ends rigid{0.0, 0.0};
  for (ContactNormal normal : {ContactNormal::chord, ContactNormal::deflected})
    for (double psi : {0.0, 0.05})
      for (double angle : {0.0, 1.3, -2.1})
        for (auto [ti, tj] : {std::pair{0.0, 0.0}, std::pair{0.3, -0.2}, std::pair{-0.1, 0.25}})
          for (double slide : {0.0, 0.35, -0.42})  // α 0.4, 0.75, −0.02
            for (Ends ends : {rigid, tsm::test::connections[0], tsm::test::connections[4]})
              for (double share : {0.5, -0.6, 2.0, -3.0}) {
                const ContactTrialSpec spec = spec_of(psi, angle, ti, tj, slide);
                const ContactTrial t = frictional(spec, normal, ends, share);
                const ContactResponse r = contact_response(t.data, t.d, t.previous);
                ASSERT_EQ(r.friction.status, std::abs(share) < 1 ? FrictionStatus::stick : FrictionStatus::slip)
                    << describe_friction(spec, normal, ends, share);
                // A step well inside the push's depth (the law bends on that scale beyond the span).
                const Matrix9 fd = differenced_tangent(t, std::min(1e-6, 1e-4 * spec.push));
                const double error = (r.tangent - fd).norm() / fd.norm();
                if (error > worst) worst = error, where = describe_friction(spec, normal, ends, share);
                const Matrix9 split =
                    r.symmetric_tangent + r.sliding_u * r.sliding_v.transpose() + r.friction_u * r.friction_v.transpose();
                EXPECT_LE((split - r.tangent).norm(), 1e-13 * r.tangent.norm());
                EXPECT_LE((r.symmetric_tangent - r.symmetric_tangent.transpose()).norm(), 1e-13 * r.tangent.norm());
                expect_self_equilibrated(t, r.nodal_forces);
              }
  EXPECT_LE(worst, 1e-6) << where;
  std::printf("friction's tangent against central differences: worst ‖K − K_fd‖/‖K_fd‖ %.2e\n", worst);
}

TEST(Friction, SlipForceIsMuTimesTheCompressionAlongTheBentNormal) {
  for (ContactNormal normal : {ContactNormal::chord, ContactNormal::deflected})
    for (double share : {2.0, -2.0}) {
      const ContactTrial t = frictional(spec_of(0.0, 0.8, 0.3, -0.2, 0.1), normal, {0.0, 0.0}, share);
      const ContactResponse r = contact_response(t.data, t.d, t.previous, false);
      ASSERT_EQ(r.friction.status, FrictionStatus::slip);
      const double compression = -t.data.friction.side * r.friction.normal_Y;
      EXPECT_NEAR(std::abs(r.friction.Z), mu * compression, 1e-13 * compression);
      EXPECT_GT(share * r.friction.Z, 0.0);  // the beam is dragged the way the point went
      // The force on the contact node: Y_N ν + Z τ (F3), ν = n − w' e, τ = e + w' n.
      const Eigen::Vector2d e(r.chord.cos, r.chord.sin), n(-r.chord.sin, r.chord.cos);
      const double w = r.friction.slope;
      const Eigen::Vector2d expected = r.friction.normal_Y * (n - w * e) + r.friction.Z * (e + w * n);
      EXPECT_NEAR((r.nodal_forces.segment<2>(6) - expected).norm(), 0.0, 1e-12 * expected.norm());
    }
}

TEST(Friction, RigidMotionChangesNoFrictionForce) {
  const ContactTrialSpec spec = spec_of(0.0, 0.0, 0.2, -0.1, 0.05);
  const ContactTrial t = frictional(spec, ContactNormal::deflected, {0.0, 0.0}, 0.5);
  ContactTrialSpec moved_spec = spec;
  moved_spec.angle = 1.1;
  moved_spec.shift = {3.0, -2.0};
  ContactTrial moved = tsm::test::contact_trial(moved_spec);
  moved.data = t.data;
  const ContactResponse a = contact_response(t.data, t.d, t.previous), b = contact_response(moved.data, moved.d, moved.previous);
  EXPECT_EQ(b.friction.status, FrictionStatus::stick);
  EXPECT_NEAR(a.friction.Z, b.friction.Z, 1e-9 * std::abs(a.friction.Z));
}

TEST(Friction, ZeroMuLeavesTheElementAsItWas) {
  for (ContactNormal normal : {ContactNormal::chord, ContactNormal::deflected}) {
    ContactTrial t = tsm::test::contact_trial(spec_of(0.0, 0.7, 0.2, -0.1, 0.1));
    t.data.normal = normal;
    const ContactResponse plain = contact_response(t.data, t.d, t.previous);
    t.data.friction = {.mu = 0.0, .side = -1, .anchored = true, .anchor = 5.0, .arc_start = 1.0};
    const ContactResponse r = contact_response(t.data, t.d, t.previous);
    EXPECT_EQ(r.friction.status, FrictionStatus::none);
    EXPECT_TRUE(r.nodal_forces == plain.nodal_forces);
    EXPECT_TRUE(r.tangent == plain.tangent);
    EXPECT_TRUE(r.friction_u.isZero() && r.friction_v.isZero());
  }
}

// ---- Several points on one element (the k-point element, along the chords' normals) ----

/// A k-point trial with friction at every point, each anchor put at `shares[p]` times its bound
/// (cycled): the points stick or slip each their own way.
tsm::test::MultiTrial frictional_points(const tsm::test::MultiSpec& spec, const std::vector<double>& shares) {
  tsm::test::MultiTrial t = tsm::test::multi_trial(spec);
  const MultiPointResponse plain = multi_point_response(t.data, t.d, t.previous, false);
  for (int p = 0; p < t.data.size(); ++p) {
    const double Y = plain.forces[3 + p], share = shares[static_cast<size_t>(p) % shares.size()];
    FrictionData& f = t.data.points[p].friction;
    f.mu = mu;
    f.side = Y > 0.0 ? -1 : 1;
    f.arc_start = 0.3;
    f.anchored = true;
    const double l0 = t.data.initial.length, c_T = tangential_compliance(t.data.section.EA, l0, plain.alpha[p], t.data.edge, 0.0).value;
    f.anchor = f.arc_start + l0 * plain.alpha[p] - share * mu * (-f.side * Y) * c_T;
  }
  return t;
}

TEST(Friction, SeveralPointsOnOneElementMatchCentralDifferencesInStickAndInSlip) {
  double worst = 0.0;
  for (const tsm::test::MultiSpec& base : tsm::test::bent_and_turned_cases())
    for (const Ends ends : {Ends{0.0, 0.0}, tsm::test::connections[2], tsm::test::connections[4]})
      for (const std::vector<double>& shares : {std::vector<double>{0.5, 3.0}, std::vector<double>{-2.5, -0.4, 2.0}}) {
        tsm::test::MultiSpec spec = base;
        spec.ends = ends;
        const tsm::test::MultiTrial t = frictional_points(spec, shares);
        const MultiPointResponse r = multi_point_response(t.data, t.d, t.previous);
        for (int p = 0; p < t.data.size(); ++p) {
          const double share = shares[static_cast<size_t>(p) % shares.size()];
          ASSERT_EQ(r.friction[p].status, std::abs(share) < 1 ? FrictionStatus::stick : FrictionStatus::slip);
          if (std::abs(share) > 1)
            EXPECT_NEAR(std::abs(r.friction[p].Z), mu * std::abs(r.forces[3 + p]), 1e-12 * std::abs(r.forces[3 + p]));
        }
        const Eigen::MatrixXd fd = tsm::test::multi_point_finite_difference_tangent(t, multi_point_response, 1e-7);
        worst = std::max(worst, (r.tangent - fd).norm() / fd.norm());
        EXPECT_LE((r.tangent - fd).norm(), 1e-6 * fd.norm()) << "k " << t.data.size();
        const Eigen::MatrixXd split = r.symmetric_tangent + r.sliding_u * r.sliding_v.transpose() +
                                      r.friction_u * r.friction_v.transpose();
        EXPECT_LE((split - r.tangent).norm(), 1e-12 * r.tangent.norm());
      }
  std::printf("k points' friction tangent against central differences: worst %.2e\n", worst);
}

TEST(Friction, OnePointInTheKPointFormIsTheThreeNodeElement) {
  // The k-point element with one frictional point against the three-node one, field by field.
  const ContactTrial t = frictional(spec_of(0.0, 0.9, 0.2, -0.1, 0.1), ContactNormal::chord, {0.0, 0.0}, 2.0);
  MultiPointElementData data;
  data.initial = t.data.initial;
  data.section = t.data.section;
  data.k0 = t.data.k0;
  data.edge = t.data.edge;
  data.points.push_back({t.data.contact_start, t.data.offset, ContactNormal::chord, t.data.friction});
  const MultiPointResponse k = multi_point_response(data, t.d, t.previous);
  const ContactResponse one = contact_response(t.data, t.d, t.previous);
  EXPECT_EQ(k.friction[0].status, FrictionStatus::slip);
  EXPECT_NEAR(k.friction[0].Z, one.friction.Z, 1e-14);
  EXPECT_LE((k.nodal_forces - one.nodal_forces).norm(), 1e-12 * one.nodal_forces.norm());
  EXPECT_LE((k.tangent - one.tangent).norm(), 1e-10 * one.tangent.norm());
}

}  // namespace
