// An element's deflected shape (element/deflected_shape) against beam theory worked out here,
// independently of the code: a simply supported beam under end moments M_i, M_j deflects by
//     w(ξ) = l²/(6EI) [M_i ξ(1−ξ)(2−ξ) − M_j ξ(1−ξ)(1+ξ)]      (EI w'' = m = −M_i(1−ξ) + M_j ξ)
// for both theories (under end moments the shear force is constant, so w'' = m/EI still), and its
// sections turn by θ = F M, F = l/(6EI) [2 −1; −1 2] + Ψ/(EI l) [1 1; 1 1] (the second term: the
// shear strain γ = −Ψ (M_i + M_j)/(EI l), θ = w' − γ). Hinges (M = 0 there), springs in series
// (node rotation = θ + f M), the end slopes by finite differences, the curve's rigid motion.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include "tsmframe/element/deflected_shape.hpp"

namespace {

using tsm::element::DeflectedShape;
using tsm::element::EndConnections;
using tsm::element::SectionStiffness;
using tsm::element::Vector2;
using tsm::element::Vector6;
using std::numbers::pi;
constexpr double hinge = std::numeric_limits<double>::infinity();  // a hinge's flexibility

constexpr double EI = 2.6, l0 = 0.8;
const SectionStiffness euler_bernoulli{.EA = 100.0, .EI = EI, .shear_flexibility = 0.0};
const SectionStiffness timoshenko{.EA = 100.0, .EI = EI, .shear_flexibility = 0.02};  // q = 12Ψ/l0² = 0.375

/// The simply supported beam's deflection under end moments (the header's closed form).
double beam_deflection(const Eigen::Vector2d& M, double xi) {
  return l0 * l0 / (6.0 * EI) * (M[0] * xi * (1 - xi) * (2 - xi) - M[1] * xi * (1 - xi) * (1 + xi));
}

/// Its end rotations per unit end moment (the header's F).
Eigen::Matrix2d beam_flexibility(const SectionStiffness& s) {
  Eigen::Matrix2d F;
  F << 2.0, -1.0, -1.0, 2.0;
  F *= l0 / (6.0 * EI);
  return F + Eigen::Matrix2d::Constant(s.shear_flexibility / (EI * l0));
}

/// The largest |w_shape(s) − w_beam(s)| over 41 points of the element.
double largest_difference(const DeflectedShape& shape, const Eigen::Vector2d& M) {
  double largest = 0.0;
  for (int k = 0; k <= 40; ++k) largest = std::max(largest, std::abs(shape.deflection(k / 40.0) - beam_deflection(M, k / 40.0)));
  return largest;
}

DeflectedShape shape_of(const SectionStiffness& s, double node_i, double node_j, EndConnections ends = {}) {
  return tsm::element::deflected_shape(s, l0, {node_i, node_j}, ends);
}

TEST(DeflectedShape, EulerBernoulliEndRotationsGiveTheHermiteCubics) {
  // One end turned, the other held: l0 θ ξ(1−ξ)² and −l0 θ ξ²(1−ξ); both turned opposite ways
  // (uniform bending): the parabola l0 θ ξ(1−ξ). Tolerance: rounding, 1e-15 of l0 θ.
  const double theta = 0.07, tol = 1e-15 * l0 * theta;
  for (int k = 0; k <= 20; ++k) {
    const double xi = k / 20.0;
    EXPECT_NEAR(shape_of(euler_bernoulli, theta, 0.0).deflection(xi), l0 * theta * xi * (1 - xi) * (1 - xi), tol);
    EXPECT_NEAR(shape_of(euler_bernoulli, 0.0, theta).deflection(xi), -l0 * theta * xi * xi * (1 - xi), tol);
    EXPECT_NEAR(shape_of(euler_bernoulli, theta, -theta).deflection(xi), l0 * theta * xi * (1 - xi), tol);
  }
  EXPECT_EQ(shape_of(euler_bernoulli, theta, 0.3).deflection(0.0), 0.0);  // the ends stay on the chord
  EXPECT_EQ(shape_of(euler_bernoulli, theta, 0.3).deflection(1.0), 0.0);
}

TEST(DeflectedShape, EulerBernoulliIsTheSimplySupportedBeamUnderItsEndMoments) {
  // M given; the element is handed the end rotations F M of beam theory. Tolerance 1e-14 of the
  // largest deflection (a dozen roundings).
  for (const Eigen::Vector2d& M : {Eigen::Vector2d(-1.0, 1.0), Eigen::Vector2d(0.7, 0.0), Eigen::Vector2d(0.3, 2.0)}) {
    const Eigen::Vector2d theta = beam_flexibility(euler_bernoulli) * M;
    const DeflectedShape shape = shape_of(euler_bernoulli, theta[0], theta[1]);
    EXPECT_LT(largest_difference(shape, M), 1e-14 * l0 * l0 / EI * M.cwiseAbs().maxCoeff()) << M.transpose();
  }
  // Sagging (M_i < 0 < M_j) bends the beam towards −n, by M l²/(8EI) at mid-span.
  const Eigen::Vector2d theta = beam_flexibility(euler_bernoulli) * Eigen::Vector2d(-1.0, 1.0);
  EXPECT_NEAR(shape_of(euler_bernoulli, theta[0], theta[1]).deflection(0.5), -l0 * l0 / (8.0 * EI), 1e-15);
}

TEST(DeflectedShape, TimoshenkoIsTheSimplySupportedBeamWithTheShearInItsEndRotations) {
  // The same deflection for the same moments, reached by end rotations that carry the shear
  // strain; the Euler–Bernoulli shape of those rotations is measurably off (so the test can fail).
  for (const Eigen::Vector2d& M : {Eigen::Vector2d(0.7, 0.0), Eigen::Vector2d(0.3, 2.0), Eigen::Vector2d(1.0, 1.0)}) {
    const Eigen::Vector2d theta = beam_flexibility(timoshenko) * M;
    const double scale = l0 * l0 / EI * M.cwiseAbs().maxCoeff();
    EXPECT_LT(largest_difference(shape_of(timoshenko, theta[0], theta[1]), M), 1e-14 * scale) << M.transpose();
    EXPECT_GT(largest_difference(shape_of(euler_bernoulli, theta[0], theta[1]), M), 1e-3 * scale) << M.transpose();
  }
}

TEST(DeflectedShape, ItsShapeFunctionsAreTheFixedEndMomentsOfAUnitPointLoad) {
  // Maxwell–Betti, what the contact law's h = −N rests on: a clamped beam under a unit point load
  // at a has fixed-end moments a b (b + q l/2) / (l²(1 + q)) and a b (a + q l/2) / (l²(1 + q))
  // (Timoshenko; q = 0: a b²/l², a² b/l²), h_i = −N_i(a/l), h_j = −N_j(a/l) in our signs.
  for (const SectionStiffness& s : {euler_bernoulli, timoshenko}) {
    const double q = 12.0 * s.shear_flexibility / (l0 * l0);
    for (const double xi : {0.1, 0.5, 0.77}) {
      const double a = xi * l0, b = l0 - a;
      const tsm::element::RotationShape N = tsm::element::rotation_shape(s, l0, xi);
      EXPECT_NEAR(N.i, a * b * (b + q * l0 / 2) / (l0 * l0 * (1 + q)), 1e-15);
      EXPECT_NEAR(N.j, -a * b * (a + q * l0 / 2) / (l0 * l0 * (1 + q)), 1e-15);
    }
  }
}

TEST(DeflectedShape, AHingedEndCarriesNoMoment) {
  // Hinged at j: the beam under M_i alone, M_i = θ_i / F_ii, whatever the node at j does; hinged
  // at i likewise. Tolerance 1e-14 of the largest deflection.
  for (const SectionStiffness& s : {euler_bernoulli, timoshenko}) {
    const Eigen::Matrix2d F = beam_flexibility(s);
    const double theta = 0.05, scale = l0 * theta;
    const DeflectedShape at_j = shape_of(s, theta, 0.9, {.flexibility_j = hinge});
    EXPECT_LT(largest_difference(at_j, {theta / F(0, 0), 0.0}), 1e-14 * scale);
    const DeflectedShape at_i = shape_of(s, -0.4, theta, {.flexibility_i = hinge});
    EXPECT_LT(largest_difference(at_i, {0.0, theta / F(1, 1)}), 1e-14 * scale);
  }
  // Euler–Bernoulli in numbers: l0 θ (2ξ − 3ξ² + ξ³)/2.
  EXPECT_NEAR(shape_of(euler_bernoulli, 0.05, 0.9, {.flexibility_j = hinge}).deflection(0.25),
              l0 * 0.05 * (0.5 - 3.0 / 16 + 1.0 / 64) / 2, 1e-16);
}

TEST(DeflectedShape, AnElementHingedAtBothEndsIsStraight) {
  // A pin-jointed bar carries no moment: w ≡ 0 whatever its nodes turn (within 1e-15 of l0 θ).
  for (const SectionStiffness& s : {euler_bernoulli, timoshenko})
    for (const double theta : {0.3, -2.0, 40.0}) {
      const DeflectedShape shape = shape_of(s, theta, -0.5 * theta, {.flexibility_i = hinge, .flexibility_j = hinge});
      for (int k = 0; k <= 16; ++k) EXPECT_LE(std::abs(shape.deflection(k / 16.0)), 1e-15 * l0 * std::abs(theta));
    }
}

TEST(DeflectedShape, EndSpringsAreInSeriesWithTheElement) {
  // Node rotations ϑ = (F + diag(f_i, f_j)) M: the moments, then the beam's deflection
  // (1e-13 of the largest deflection).
  const Eigen::Vector2d node(0.04, -0.03);
  for (const SectionStiffness& s : {euler_bernoulli, timoshenko})
    for (const auto& [fi, fj] : {std::pair{0.1, 0.0}, std::pair{0.0, 0.5}, std::pair{0.2, 3.0}}) {
      const Eigen::Vector2d M = (beam_flexibility(s) + Eigen::Vector2d(fi, fj).asDiagonal().toDenseMatrix()).inverse() * node;
      const DeflectedShape shape = shape_of(s, node[0], node[1], {.flexibility_i = fi, .flexibility_j = fj});
      EXPECT_LT(largest_difference(shape, M), 1e-13 * l0 * node.cwiseAbs().maxCoeff()) << fi << ' ' << fj;
    }
  // By hand, Euler–Bernoulli with a spring at i only and node j held: M_i = 4EI θ/l0 at the
  // element's end, so θ = ϑ_i / (1 + 4EI f/l0), and the shape is l0 θ ξ(1−ξ)².
  const double f = 0.3, theta = 0.04 / (1.0 + 4.0 * EI * f / l0);
  EXPECT_NEAR(shape_of(euler_bernoulli, 0.04, 0.0, {.flexibility_i = f}).deflection(0.3), l0 * theta * 0.3 * 0.7 * 0.7, 1e-16);
}

TEST(DeflectedShape, EndSpringsTendToRigidAndToAHinge) {
  // f → 0: the rigid element's shape; f → ∞: the hinged one's; each to about f·k or 1/(f·k).
  const Eigen::Vector2d node(0.04, -0.03);
  for (const SectionStiffness& s : {euler_bernoulli, timoshenko}) {
    const double soft = 1e9 * l0 / EI, stiff = 1e-9 * l0 / EI;
    const DeflectedShape rigid = shape_of(s, node[0], node[1]);
    const DeflectedShape hinged = shape_of(s, node[0], node[1], {.flexibility_j = hinge});
    const DeflectedShape both_hinged = shape_of(s, node[0], node[1], {.flexibility_i = hinge, .flexibility_j = hinge});
    const DeflectedShape nearly_rigid = shape_of(s, node[0], node[1], {.flexibility_i = stiff, .flexibility_j = stiff});
    const DeflectedShape nearly_hinged = shape_of(s, node[0], node[1], {.flexibility_j = soft});
    const DeflectedShape nearly_bar = shape_of(s, node[0], node[1], {.flexibility_i = soft, .flexibility_j = soft});
    const double scale = l0 * node.cwiseAbs().maxCoeff();
    for (int k = 0; k <= 10; ++k) {
      const double xi = k / 10.0;
      EXPECT_NEAR(nearly_rigid.deflection(xi), rigid.deflection(xi), 1e-8 * scale);
      EXPECT_NEAR(nearly_hinged.deflection(xi), hinged.deflection(xi), 1e-8 * scale);
      EXPECT_NEAR(nearly_bar.deflection(xi), both_hinged.deflection(xi), 1e-8 * scale);
    }
    EXPECT_GT(std::abs(rigid.deflection(0.5) - hinged.deflection(0.5)), 1e-3 * scale);  // the limits differ
  }
}

TEST(DeflectedShape, TheEndSlopesAreTheElementsEndRotationsAndItsShear) {
  // Central differences of w inside, second-order one-sided ones at the ends (h = 1e-5: the
  // truncation ~h² w''' and rounding ~1e-16/h leave 1e-9 of θ). Euler–Bernoulli: w' = θ at the
  // ends; Timoshenko: w' = θ + γ, γ = −Ψ (M_i + M_j)/(EI l0), with M and θ from the series
  // formula above (a spring's end turns f M less than its node; a hinge's M = 0).
  const Eigen::Vector2d node(0.06, 0.02);
  for (const SectionStiffness& s : {euler_bernoulli, timoshenko})
    for (const auto& [fi, fj] : {std::pair{0.0, 0.0}, std::pair{0.2, 0.0}, std::pair{0.2, 3.0}, std::pair{hinge, 0.1}}) {
      const DeflectedShape shape = shape_of(s, node[0], node[1], {.flexibility_i = fi, .flexibility_j = fj});
      Eigen::Vector2d M;
      if (std::isinf(fi)) {
        M = Eigen::Vector2d(0.0, node[1] / (beam_flexibility(s)(1, 1) + fj));
      } else {
        M = (beam_flexibility(s) + Eigen::Vector2d(fi, fj).asDiagonal().toDenseMatrix()).inverse() * node;
      }
      const Eigen::Vector2d theta = beam_flexibility(s) * M;  // the element's own end rotations
      if (!std::isinf(fi)) EXPECT_NEAR(theta[0], node[0] - fi * M[0], 1e-15);
      const double gamma = -s.shear_flexibility * (M[0] + M[1]) / (EI * l0), h = 1e-5;
      const auto w = [&](double xi) { return shape.deflection(xi); };
      const double start = (-3 * w(0) + 4 * w(h) - w(2 * h)) / (2 * h * l0);
      const double end = (3 * w(1) - 4 * w(1 - h) + w(1 - 2 * h)) / (2 * h * l0);
      EXPECT_NEAR(start, theta[0] + gamma, 1e-9) << fi << ' ' << fj;
      EXPECT_NEAR(end, theta[1] + gamma, 1e-9) << fi << ' ' << fj;
      EXPECT_NEAR(shape.slope(0.0), theta[0] + gamma, 1e-14);
      EXPECT_NEAR(shape.slope(1.0), theta[1] + gamma, 1e-14);
      for (const double xi : {0.2, 0.5, 0.9})
        EXPECT_NEAR(shape.slope(xi), (w(xi + h) - w(xi - h)) / (2 * h * l0), 1e-9) << xi;
    }
}

/// The curve's points for one element state.
std::array<Vector2, 9> curve(const tsm::element::InitialChord& initial, const Vector6& d, double beta,
                             const SectionStiffness& s, EndConnections ends) {
  std::array<Vector2, 9> points;
  tsm::element::deflected_curve(initial, d, beta, s, ends, points);
  return points;
}

TEST(DeflectedCurve, LiesOnTheChordPlusTheShapeAlongItsNormal) {
  // Drawn from (1, 2) to (1.48, 2.64) (l0 = 0.8), moved and turned: its end points are the nodes'
  // positions, the others the chord's points plus w n (1e-14: a few ulps of coordinates near 3).
  const tsm::element::InitialChord initial = tsm::element::initial_chord({1.0, 2.0}, {1.48, 2.64});
  Vector6 d;
  d << 0.1, -0.2, 0.5, -0.05, 0.1, 0.45;
  const double beta = std::atan2(0.94, 0.33) - std::atan2(0.64, 0.48);  // the current chord's turn
  const std::array<Vector2, 9> points = curve(initial, d, beta, timoshenko, {});
  const Vector2 xi(1.1, 1.8), xj(1.43, 2.74), n = Vector2(-0.94, 0.33).normalized();
  const DeflectedShape shape = shape_of(timoshenko, 0.5 - beta, 0.45 - beta);
  for (int k = 0; k <= 8; ++k) {
    const Vector2 expected = xi + k / 8.0 * (xj - xi) + shape.deflection(k / 8.0) * n;
    EXPECT_LT((points[k] - expected).norm(), 1e-14) << k;
  }
  EXPECT_LT((points[0] - xi).norm(), 1e-14);
  EXPECT_LT((points[8] - xj).norm(), 1e-14);
  EXPECT_GT(std::abs(shape.deflection(0.5)), 1e-3);  // it does bend
}

TEST(DeflectedCurve, MovesRigidlyWithTheElement) {
  // Turning the whole state by ρ about the origin (chord rotation and node rotations by ρ too,
  // several whole turns included) and moving it by t turns and moves the curve alike (1e-14 of
  // the size), hinged and sprung elements included.
  const tsm::element::InitialChord initial = tsm::element::initial_chord({1.0, 2.0}, {1.48, 2.64});
  Vector6 d;
  d << 0.1, -0.2, 0.5, -0.05, 0.1, 0.45;
  const double beta = std::atan2(0.94, 0.33) - std::atan2(0.64, 0.48);
  const Vector2 t(-3.0, 0.7);
  for (const EndConnections ends : {EndConnections{}, EndConnections{hinge, 0.0}, EndConnections{0.3, 1.0}})
    for (const SectionStiffness& s : {euler_bernoulli, timoshenko})
      for (const double rho : {0.4, -2.5, 6 * pi + 1.1}) {
        const Eigen::Rotation2Dd R(rho);
        Vector6 moved;
        moved.segment<2>(0) = R * (initial.start + d.segment<2>(0)) + t - initial.start;
        moved.segment<2>(3) = R * (initial.end + d.segment<2>(3)) + t - initial.end;
        moved[2] = d[2] + rho;
        moved[5] = d[5] + rho;
        const std::array<Vector2, 9> before = curve(initial, d, beta, s, ends), after = curve(initial, moved, beta + rho, s, ends);
        for (int k = 0; k <= 8; ++k) EXPECT_LT((after[k] - (R * before[k] + t)).norm(), 1e-14 * 4.0) << rho << ' ' << k;
      }
}

}  // namespace
