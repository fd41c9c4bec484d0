#pragma once
// A three-node contact element in a deformed state, for the element tests: the beam element
// from (0.3, −0.2) to (1.3, 0.4) with a contact node drawn at α0 on its axis, turned rigidly by
// `angle` about node i, stretched by 0.2 %, bent (θ_i, θ_j), the node moved off the chord by
// `push` along n and by `slide` along e, everything then shifted by `shift`.

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "tsmframe/contact/contact_response.hpp"

namespace tsm::test {

struct ContactTrialSpec {
  double psi = 0.0, angle = 0.0, theta_i = 0.0, theta_j = 0.0, alpha0 = 0.4, push = 0.0, slide = 0.0;
  bool sliding_term = true;
  bool cantilever_frame = false;
  Eigen::Vector2d shift = Eigen::Vector2d::Zero();
  double node_rotation = 0.7;  ///< Θ of the contact node
};

struct ContactTrial {
  contact::ContactElementData data;
  contact::Vector9 d;
  double previous = 0.0;  ///< the chord rotation to continue from
};

inline ContactTrial contact_trial(const ContactTrialSpec& p) {
  ContactTrial s;
  s.data.initial = element::initial_chord({0.3, -0.2}, {1.3, 0.4});
  s.data.section = {.EA = 400.0, .EI = 3.0, .shear_flexibility = p.psi};
  s.data.k0 = element::basic_stiffness(s.data.section, s.data.initial.length);
  const Eigen::Vector2d chord = s.data.initial.end - s.data.initial.start;
  s.data.contact_start = s.data.initial.start + p.alpha0 * chord;
  s.data.edge = 1e-3;
  s.data.sliding_term = p.sliding_term;
  s.data.frame = p.cantilever_frame ? ContactFrame::cantilever : ContactFrame::chord;
  const Eigen::Rotation2Dd R(p.angle);
  const Eigen::Vector2d end = s.data.initial.start + 1.002 * (R * chord);
  const Eigen::Vector2d e = (R * chord).normalized(), n(-e.y(), e.x());
  const Eigen::Vector2d contact = s.data.initial.start + (p.alpha0 + p.slide) * 1.002 * (R * chord) + p.push * n;
  s.d << p.shift.x(), p.shift.y(), p.angle + p.theta_i, end.x() - s.data.initial.end.x() + p.shift.x(),
      end.y() - s.data.initial.end.y() + p.shift.y(), p.angle + p.theta_j, contact.x() - s.data.contact_start.x() + p.shift.x(),
      contact.y() - s.data.contact_start.y() + p.shift.y(), p.node_rotation;
  s.previous = p.angle + 0.02;
  return s;
}

/// ∂(nodal forces)/∂d by central differences (h = 1e-6).
inline contact::Matrix9 finite_difference_tangent(const ContactTrial& s) {
  contact::Matrix9 K;
  for (int b = 0; b < 9; ++b) {
    const double h = 1e-6;
    contact::Vector9 plus = s.d, minus = s.d;
    plus[b] += h;
    minus[b] -= h;
    K.col(b) = (contact::contact_response(s.data, plus, s.previous).nodal_forces -
                contact::contact_response(s.data, minus, s.previous).nodal_forces) / (2 * h);
  }
  return K;
}

/// The contact element's nodal forces F at (data, d) are self-equilibrated: no net force and no
/// net moment (about the origin, at the current positions), none on the contact node's rotation.
inline void expect_self_equilibrated(const contact::ContactElementData& data, const contact::Vector9& d,
                                     const contact::Vector9& F) {
  const double scale = F.cwiseAbs().maxCoeff();
  EXPECT_NEAR(F[0] + F[3] + F[6], 0.0, 1e-12 * scale);
  EXPECT_NEAR(F[1] + F[4] + F[7], 0.0, 1e-12 * scale);
  const Eigen::Vector2d xi = data.initial.start + d.segment<2>(0), xj = data.initial.end + d.segment<2>(3),
                        xc = data.contact_start + d.segment<2>(6);
  auto cross = [](const Eigen::Vector2d& x, double fx, double fy) { return x.x() * fy - x.y() * fx; };
  const double moment = F[2] + F[5] + F[8] + cross(xi, F[0], F[1]) + cross(xj, F[3], F[4]) + cross(xc, F[6], F[7]);
  EXPECT_NEAR(moment, 0.0, 3e-12 * scale);
  EXPECT_EQ(F[8], 0.0);  // the contact node takes no moment
}

}  // namespace tsm::test
