// The two-node element: tangent against central finite differences of J S (Eq. 2), at end
// rotations of several radians and after rigid rotations of 3π; no force under rigid motion.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

#include "tsmframe/element/beam_element.hpp"
#include "tsmframe/element/force_law.hpp"

namespace test_beam_element {
namespace {

using namespace tsm::element;
using std::numbers::pi;

/// Central-difference Jacobian of the nodal forces, tracking β from the same previous rotation.
Matrix6 finite_difference_tangent(const InitialChord& chord, const Matrix3& s, const Vector6& d,
                                  double previous) {
  Matrix6 K;
  for (int b = 0; b < 6; ++b) {
    const double h = 1e-6 * (b % 3 == 2 ? 1.0 : chord.length);
    Vector6 plus = d, minus = d;
    plus[b] += h;
    minus[b] -= h;
    K.col(b) = (beam_response(chord, s, plus, previous).nodal_forces -
                beam_response(chord, s, minus, previous).nodal_forces) / (2 * h);
  }
  return K;
}

/// End displacements that rotate the element rigidly by `angle` about node i, stretch it by
/// `stretch`, and turn the ends by θ_i, θ_j relative to the chord.
Vector6 deformed(const InitialChord& c, double angle, double stretch, double theta_i, double theta_j) {
  const Vector2 chord = c.end - c.start;
  const Eigen::Rotation2Dd R(angle);
  const Vector2 end = c.start + (1.0 + stretch) * (R * chord);
  Vector6 d;
  d << 0.0, 0.0, angle + theta_i, end.x() - c.end.x(), end.y() - c.end.y(), angle + theta_j;
  return d;
}

struct Case {
  double shear_flexibility;
  double angle;
  double stretch;
  double theta_i, theta_j;
  bool hinge_i = false, hinge_j = false;  ///< a member "release" at that end (released_stiffness)
  double spring_i = 0.0, spring_j = 0.0;  ///< flexibility of an end spring (connected_stiffness)
};

class BeamTangent : public ::testing::TestWithParam<Case> {};

TEST_P(BeamTangent, MatchesFiniteDifferences) {
  const Case& p = GetParam();
  const InitialChord chord = initial_chord({0.3, -0.2}, {2.3, 0.8});
  const SectionStiffness section{.EA = 200.0, .EI = 3.0, .shear_flexibility = p.shear_flexibility};
  const BasicStiffness k0 = basic_stiffness_terms(section, chord.length);
  const Matrix3 s = p.spring_i > 0.0 || p.spring_j > 0.0 ? connected_stiffness(k0, p.spring_i, p.spring_j)
                    : p.hinge_i || p.hinge_j           ? released_stiffness(k0, p.hinge_i, p.hinge_j)
                                                       : basic_stiffness(section, chord.length);
  const Vector6 d = deformed(chord, p.angle, p.stretch, p.theta_i, p.theta_j);
  const double previous = p.angle + 0.01;  // the previous iterate's β, close to the current one
  const BeamResponse r = beam_response(chord, s, d, previous);
  if (p.hinge_i) EXPECT_EQ(r.forces[1], 0.0) << "a hinge carries no moment";
  if (p.hinge_j) EXPECT_EQ(r.forces[2], 0.0) << "a hinge carries no moment";
  if (p.hinge_i) EXPECT_EQ(r.tangent.row(2).norm(), 0.0) << "node i's rotation is not the element's";
  EXPECT_NEAR(r.chord.rotation, p.angle, 1e-12);
  const Matrix6 fd = finite_difference_tangent(chord, s, d, previous);
  const double error = (r.tangent - fd).cwiseAbs().maxCoeff() / r.tangent.cwiseAbs().maxCoeff();
  EXPECT_LE(error, 1e-6) << "analytic\n" << r.tangent << "\nfinite differences\n" << fd;
  EXPECT_LE((r.tangent - r.tangent.transpose()).cwiseAbs().maxCoeff(), 1e-12 * r.tangent.cwiseAbs().maxCoeff());
  // The closed form equals the textbook products J k0 Jᵀ + K_G and J S (FORMULATION §1).
  const EquilibriumMatrix J = equilibrium_matrix(r.chord);
  const Matrix6 products = J * s * J.transpose() + geometric_stiffness(r.chord, r.forces);
  EXPECT_LE((r.tangent - products).cwiseAbs().maxCoeff(), 1e-13 * r.tangent.cwiseAbs().maxCoeff());
  EXPECT_LE((r.nodal_forces - J * r.forces).cwiseAbs().maxCoeff(), 1e-13 * r.nodal_forces.cwiseAbs().maxCoeff());
}

INSTANTIATE_TEST_SUITE_P(
    LargeRotations, BeamTangent,
    ::testing::Values(Case{0.0, 0.0, 0.0, 0.0, 0.0}, Case{0.0, 0.4, 0.02, 2.5, -1.7},
                      Case{0.0, 3 * pi, 0.05, 2.5, -1.7}, Case{0.0, -3 * pi, -0.03, -2.9, 2.2},
                      Case{0.05, 3 * pi, 0.05, 2.5, -1.7}, Case{0.05, 1.0, -0.02, 3.1, 3.1},
                      Case{0.5, -3 * pi + 0.3, 0.01, -1.2, 2.7},
                      // hinged (a member "release"), either end or both, Euler–Bernoulli and Timoshenko
                      Case{0.0, 0.4, 0.02, 2.5, -1.7, true, false}, Case{0.0, 3 * pi, 0.02, 2.5, -1.7, false, true},
                      Case{0.0, 0.4, 0.02, 2.5, -1.7, true, true}, Case{0.05, 3 * pi, 0.02, 2.5, -1.7, true, false},
                      Case{0.05, 0.4, 0.02, 2.5, -1.7, false, true},
                      // semi-rigid: end springs (member "end_springs"), one end or both, and beside a hinge
                      Case{0.0, 0.4, 0.02, 2.5, -1.7, false, false, 0.3, 0.0}, Case{0.05, 3 * pi, 0.02, 2.5, -1.7, false, false, 0.3, 0.1},
                      Case{0.0, 0.4, 0.02, 2.5, -1.7, false, false, INFINITY, 0.2}));

TEST(BeamElement, RigidMotionGivesNoForce) {
  const InitialChord chord = initial_chord({1.0, 2.0}, {4.0, -2.0});
  const SectionStiffness section{.EA = 2e11, .EI = 1e5, .shear_flexibility = 1e-6};
  const Matrix3 s = basic_stiffness(section, chord.length);
  for (double angle : {0.0, 0.3, 3 * pi, -5.0, 4 * pi + 0.1}) {
    const Eigen::Rotation2Dd R(angle);
    const Vector2 t(-3.0, 7.5);
    const Vector2 xi = R * chord.start + t, xj = R * chord.end + t;
    Vector6 d;
    d << xi.x() - chord.start.x(), xi.y() - chord.start.y(), angle, xj.x() - chord.end.x(), xj.y() - chord.end.y(),
        angle;
    const BeamResponse r = beam_response(chord, s, d, angle - 0.2);
    EXPECT_NEAR(r.chord.rotation, angle, 1e-12);
    // Round-off floor: ε · EA/l0 · |x| for N, ε · EI/l0 for M.
    EXPECT_LE(std::abs(r.forces[0]), 1e-14 * section.EA / chord.length * 10.0) << angle;
    EXPECT_LE(std::abs(r.forces[1]), 1e-13 * section.EI / chord.length) << angle;
    EXPECT_LE(std::abs(r.forces[2]), 1e-13 * section.EI / chord.length) << angle;
  }
}

TEST(BeamElement, ChordRotationIsTrackedThroughManyTurns) {
  // Turning the element in steps of 0.5 rad continues β past ±π without wrapping.
  const InitialChord chord = initial_chord({0.0, 0.0}, {1.0, 0.0});
  const Matrix3 s = basic_stiffness({.EA = 1.0, .EI = 1.0, .shear_flexibility = 0.0}, chord.length);
  double beta = 0.0;
  for (int k = 1; k <= 30; ++k) {
    const double angle = 0.5 * k;
    Vector6 d;
    d << 0.0, 0.0, angle, std::cos(angle) - 1.0, std::sin(angle), angle;
    beta = beam_response(chord, s, d, beta).chord.rotation;
    EXPECT_NEAR(beta, angle, 1e-12);
  }
}

TEST(BeamElement, EquilibriumOfNodalForces) {
  // J S is self-equilibrated: Σ F = 0 and Σ M about the origin = 0 in the current geometry.
  const InitialChord chord = initial_chord({0.0, 0.0}, {2.0, 1.0});
  const Matrix3 s = basic_stiffness({.EA = 50.0, .EI = 2.0, .shear_flexibility = 0.1}, chord.length);
  const Vector6 d = deformed(chord, 2.0, 0.1, 0.7, -0.4);
  const BeamResponse r = beam_response(chord, s, d, 2.0);
  const Vector6& F = r.nodal_forces;
  EXPECT_NEAR(F[0] + F[3], 0.0, 1e-12);
  EXPECT_NEAR(F[1] + F[4], 0.0, 1e-12);
  const Vector2 xi = chord.start + Vector2(d[0], d[1]), xj = chord.end + Vector2(d[3], d[4]);
  const double moment = F[2] + F[5] + (xi.x() * F[1] - xi.y() * F[0]) + (xj.x() * F[4] - xj.y() * F[3]);
  EXPECT_NEAR(moment, 0.0, 1e-12);
  EXPECT_GT(r.forces.norm(), 1.0);  // a real force state, not a trivial zero
}

TEST(BeamElement, KeptStiffnessTermsGiveTheFullMatrixBitForBit) {
  // The element loop passes k0 as its three kept terms (BasicStiffness); every result must be
  // exactly what the 3×3 k0 gives, for Euler–Bernoulli and Timoshenko, on all branches of β.
  const InitialChord chord = initial_chord({0.3, -0.2}, {2.3, 0.8});
  for (const double psi : {0.0, 0.05, 0.5}) {
    const SectionStiffness section{.EA = 200.0, .EI = 3.0, .shear_flexibility = psi};
    const BasicStiffness terms = basic_stiffness_terms(section, chord.length);
    const Matrix3 full = basic_stiffness(section, chord.length);
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) EXPECT_EQ(terms(a, b), full(a, b)) << a << "," << b;
    for (const double angle : {0.0, 0.4, 3 * pi, -3 * pi + 0.3}) {
      const Vector6 d = deformed(chord, angle, 0.02, 2.5, -1.7);
      const BeamResponse x = beam_response(chord, terms, d, angle + 0.01);
      const BeamResponse y = beam_response(chord, full, d, angle + 0.01);
      EXPECT_EQ(x.chord.rotation, y.chord.rotation);
      EXPECT_TRUE((x.forces.array() == y.forces.array()).all()) << x.forces.transpose() << " | " << y.forces.transpose();
      EXPECT_TRUE((x.nodal_forces.array() == y.nodal_forces.array()).all());
      EXPECT_TRUE((x.tangent.array() == y.tangent.array()).all());
      EXPECT_GT(x.forces.norm(), 1.0);  // a real force state
    }
  }
}

}  // namespace

}  // namespace test_beam_element
