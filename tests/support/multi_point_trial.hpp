#pragma once
// A k-point contact element in a deformed state, for the k-point elements' tests (the element of
// contact_trial.hpp with k contact nodes): the beam element from (0.3, −0.2) to (1.3, 0.4), turned
// rigidly by `angle` about node i, stretched by 0.2 %, bent (θ_i, θ_j); contact node p drawn on the
// axis at alpha0[p], then moved by push[p] along n and by slide[p] (in α) along e, its own rotation
// 0.7 + p. The central-difference tangent and the self-equilibrium check of such an element's
// nodal forces go with it.

#include <gtest/gtest.h>

#include <algorithm>
#include <ostream>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "support/end_connections.hpp"
#include "tsmframe/contact/multi_point_element.hpp"

namespace tsm::test {

struct MultiTrial {
  contact::MultiPointElementData data;
  Eigen::VectorXd d;
  double previous = 0.0;  ///< the chord rotation to continue from
};

struct MultiSpec {
  double psi = 0.0, angle = 0.0, theta_i = 0.0, theta_j = 0.0;
  std::vector<double> alpha0, push, slide;
  Ends ends{0.0, 0.0};
  bool sliding_term = true;
  ContactNormal normal = ContactNormal::chord;  ///< every point's normal …
  std::vector<int> chord_points;                ///< … but these points' (a mixed element)
};

inline MultiTrial multi_trial(const MultiSpec& p) {
  MultiTrial s;
  s.data.initial = element::initial_chord({0.3, -0.2}, {1.3, 0.4});
  s.data.section = {.EA = 400.0, .EI = 3.0, .shear_flexibility = p.psi};
  s.data.k0 = element::basic_stiffness(s.data.section, s.data.initial.length);
  s.data.edge = 1e-3;
  s.data.sliding_term = p.sliding_term;
  s.data.flexibility_i = p.ends.i;
  s.data.flexibility_j = p.ends.j;
  const int k = static_cast<int>(p.alpha0.size());
  const Eigen::Vector2d chord = s.data.initial.end - s.data.initial.start;
  const Eigen::Rotation2Dd R(p.angle);
  const Eigen::Vector2d end = s.data.initial.start + 1.002 * (R * chord);
  const Eigen::Vector2d e = (R * chord).normalized(), n(-e.y(), e.x());
  s.d.resize(3 * (2 + k));
  s.d.head<6>() << 0.0, 0.0, p.angle + p.theta_i, end.x() - s.data.initial.end.x(), end.y() - s.data.initial.end.y(),
      p.angle + p.theta_j;
  for (int q = 0; q < k; ++q) {
    const Eigen::Vector2d start = s.data.initial.start + p.alpha0[q] * chord;
    const bool chord_point = std::find(p.chord_points.begin(), p.chord_points.end(), q) != p.chord_points.end();
    s.data.points.push_back({start, 0.0, chord_point ? ContactNormal::chord : p.normal});
    const Eigen::Vector2d at = s.data.initial.start + (p.alpha0[q] + p.slide[q]) * 1.002 * (R * chord) + p.push[q] * n;
    s.d.segment<3>(6 + 3 * q) << at.x() - start.x(), at.y() - start.y(), 0.7 + q;
  }
  s.previous = p.angle + 0.02;
  return s;
}

/// ∂(nodal forces)/∂d of `respond` (multi_point_response or an element of the same signature) by
/// central differences of step h.
template <class Respond>
Eigen::MatrixXd multi_point_finite_difference_tangent(const MultiTrial& s, Respond respond, double h = 1e-6) {
  const int size = static_cast<int>(s.d.size());
  Eigen::MatrixXd K(size, size);
  for (int b = 0; b < size; ++b) {
    Eigen::VectorXd plus = s.d, minus = s.d;
    plus[b] += h;
    minus[b] -= h;
    K.col(b) = (respond(s.data, plus, s.previous, false).nodal_forces -
                respond(s.data, minus, s.previous, false).nodal_forces) / (2 * h);
  }
  return K;
}

/// Bent elements turned 1–2 rad with k = 2, 3, 5 points, both theories: the cases every k-point
/// element's tangent is checked at against central differences.
inline std::vector<MultiSpec> bent_and_turned_cases() {
  return {MultiSpec{.psi = 0.0, .angle = 1.2, .theta_i = 0.2, .theta_j = -0.1, .alpha0 = {0.3, 0.65},
                    .push = {2e-2, 1e-2}, .slide = {0.05, -0.02}},
          MultiSpec{.psi = 0.01, .angle = -2.0, .theta_i = -0.3, .theta_j = 0.25, .alpha0 = {0.2, 0.7},
                    .push = {-1e-2, -2e-2}, .slide = {0.1, 0.0}},
          MultiSpec{.psi = 0.0, .angle = 1.7, .theta_i = 0.3, .theta_j = 0.1, .alpha0 = {0.15, 0.45, 0.8},
                    .push = {1e-2, 3e-2, 1.5e-2}, .slide = {0.02, -0.05, 0.03}},
          MultiSpec{.psi = 0.005, .angle = 1.0, .theta_i = 0.15, .theta_j = -0.25, .alpha0 = {0.8, 0.2, 0.5},
                    .push = {2e-2, 1e-2, 2e-2}, .slide = {0.0, 0.05, -0.1}},
          MultiSpec{.psi = 0.0, .angle = -1.4, .theta_i = -0.2, .theta_j = 0.3, .alpha0 = {0.1, 0.3, 0.5, 0.7, 0.9},
                    .push = {1e-2, 2e-2, 3e-2, 2e-2, 1e-2}, .slide = {0.01, 0.02, -0.01, 0.0, -0.02}},
          MultiSpec{.psi = 0.02, .angle = 2.0, .theta_i = 0.25, .theta_j = 0.2, .alpha0 = {0.1, 0.3, 0.5, 0.7, 0.9},
                    .push = {-2e-2, -1e-2, -3e-2, -1e-2, -2e-2}, .slide = {0.03, -0.02, 0.01, 0.02, -0.03}}};
}

/// A case's name: k, the theory and its place in the list.
inline std::string case_name(const ::testing::TestParamInfo<MultiSpec>& info) {
  return "k" + std::to_string(info.param.alpha0.size()) + (info.param.psi > 0.0 ? "Timoshenko" : "EulerBernoulli") +
         std::to_string(info.index);
}

inline std::string describe(const MultiSpec& p) {
  return "psi " + std::to_string(p.psi) + " angle " + std::to_string(p.angle) + " k " + std::to_string(p.alpha0.size()) +
         " ends " + std::to_string(p.ends.i) + " " + std::to_string(p.ends.j);
}

/// What gtest prints for a case (its own dump would show the vectors' addresses).
inline void PrintTo(const MultiSpec& p, std::ostream* os) { *os << describe(p); }

/// The element's nodal forces F at (data, d) are self-equilibrated: no net force and no net moment
/// (about the origin, at the current positions), none on a contact node's rotation.
inline void expect_multi_point_self_equilibrated(const contact::MultiPointElementData& data, const Eigen::VectorXd& d,
                                                 const Eigen::VectorXd& F) {
  const double scale = F.cwiseAbs().maxCoeff();
  double fx = 0.0, fy = 0.0, moment = 0.0;
  for (int node = 0; node < 2 + data.size(); ++node) {
    const Eigen::Vector2d drawn = node == 0 ? data.initial.start : node == 1 ? data.initial.end : data.points[node - 2].start;
    const Eigen::Vector2d x = drawn + d.segment<2>(3 * node);
    fx += F[3 * node];
    fy += F[3 * node + 1];
    moment += F[3 * node + 2] + x.x() * F[3 * node + 1] - x.y() * F[3 * node];
    if (node >= 2) {
      EXPECT_EQ(F[3 * node + 2], 0.0);  // a contact node takes no moment
    }
  }
  EXPECT_NEAR(fx, 0.0, 1e-12 * scale);
  EXPECT_NEAR(fy, 0.0, 1e-12 * scale);
  EXPECT_NEAR(moment, 0.0, 3e-12 * scale);
}

}  // namespace tsm::test
