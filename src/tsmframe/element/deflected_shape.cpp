#include "tsmframe/element/deflected_shape.hpp"

#include <cmath>

namespace tsm::element {

// Under end moments alone the beam's moment is linear and its shear force constant, so
// EI w'' = m(x) for both theories (the shear strain γ is constant and w'' = ψ' + γ' = m/EI): with
// w(0) = w(l0) = 0 the deflection is the Euler–Bernoulli one of the same end moments. The
// Timoshenko beam differs in its end rotations, the sections' ψ = w' − γ, γ = −Ψ (M_i + M_j)/(EI l0):
// w is the bending part ∫ψ dx plus the shear part γ x. Written in θ = (ψ(0), ψ(l0)) through Eq. 4,
// it is the element's interdependent interpolation below (a = s l0, b = (1 − s) l0).

RotationShape rotation_shape(const SectionStiffness& section, double l0, double s) {
  const double psi = section.shear_flexibility, span = l0 * l0 + 12.0 * psi;
  const double a = s * l0, b = (1.0 - s) * l0, p = a * b;
  // w(s) = l0 s(1−s) [(1 − s + q/2) θ_i − (s + q/2) θ_j] / (1 + q), q = 12Ψ/l0² (Eq. 4's beam; q = 0: Eq. 3's cubic)
  return {(b * l0 + 6.0 * psi) * p / (l0 * span), -(a * l0 + 6.0 * psi) * p / (l0 * span)};
}

RotationShape rotation_shape_slope(const SectionStiffness& section, double l0, double s) {
  const double psi = section.shear_flexibility, span = l0 * l0 + 12.0 * psi;
  const double a = s * l0, b = (1.0 - s) * l0, p = a * b;
  return {l0 * ((b * l0 + 6.0 * psi) * (1.0 - 2.0 * s) - p) / span, -l0 * (p + (a * l0 + 6.0 * psi) * (1.0 - 2.0 * s)) / span};
}

Eigen::Vector2d element_end_rotations(const SectionStiffness& section, double l0, const Eigen::Vector2d& node_rotations,
                                      const EndConnections& ends) {
  const double f[2] = {ends.flexibility_i, ends.flexibility_j};
  if (f[0] == 0.0 && f[1] == 0.0) return node_rotations;  // rigid: the nodes' rotations are the element's
  const bool hinge[2] = {std::isinf(f[0]), std::isinf(f[1])};
  if (hinge[0] && hinge[1]) return Eigen::Vector2d::Zero();  // a bar: no moment, straight
  // The bending block B = [d c; c d] of Eq. 3/4 gives the element's end moments M = B θ.
  const BasicStiffness k0 = basic_stiffness_terms(section, l0);
  const double d = k0.direct, c = k0.cross;
  if (hinge[0] || hinge[1]) {
    // M_r = 0 at the hinge r: θ_r = −(c/d) θ_s; the other end s is the propped beam's, stiffness
    // d − c²/d, in series with its spring: θ_s = ϑ_s / (1 + f_s (d − c²/d)).
    const int r = hinge[0] ? 0 : 1, s = 1 - r;
    Eigen::Vector2d theta;
    theta[s] = node_rotations[s] / (1.0 + f[s] * (d - c * c / d));
    theta[r] = -(c / d) * theta[s];
    return theta;
  }
  // Springs: ϑ = θ + F M = (I + F B) θ, F = diag(f_i, f_j) — the element and its springs in series.
  const double a00 = 1.0 + f[0] * d, a01 = f[0] * c, a10 = f[1] * c, a11 = 1.0 + f[1] * d;
  const double det = a00 * a11 - a01 * a10;
  return {(a11 * node_rotations[0] - a01 * node_rotations[1]) / det, (a00 * node_rotations[1] - a10 * node_rotations[0]) / det};
}

double DeflectedShape::deflection(double s) const {
  const RotationShape N = rotation_shape(section, l0, s);
  return N.i * end_rotations[0] + N.j * end_rotations[1];
}

double DeflectedShape::slope(double s) const {
  const RotationShape dN = rotation_shape_slope(section, l0, s);
  return (dN.i * end_rotations[0] + dN.j * end_rotations[1]) / l0;
}

DeflectedShape deflected_shape(const SectionStiffness& section, double l0, const Eigen::Vector2d& node_rotations,
                               const EndConnections& ends) {
  return {section, l0, element_end_rotations(section, l0, node_rotations, ends)};
}

void deflected_curve(const InitialChord& initial, const Vector6& d, double chord_rotation,
                     const SectionStiffness& section, const EndConnections& ends, std::span<Vector2> points) {
  const Vector2 xi = initial.start + d.segment<2>(0), xj = initial.end + d.segment<2>(3);
  const double phi = std::atan2(xj.y() - xi.y(), xj.x() - xi.x());
  const Vector2 n(-std::sin(phi), std::cos(phi));
  const DeflectedShape shape =
      deflected_shape(section, initial.length, {d[2] - chord_rotation, d[5] - chord_rotation}, ends);
  const double last = static_cast<double>(points.size() - 1);
  for (size_t k = 0; k < points.size(); ++k) {
    const double s = static_cast<double>(k) / last;
    points[k] = xi + s * (xj - xi) + shape.deflection(s) * n;
  }
}

}  // namespace tsm::element
