#include "tsmframe/element/chord.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace tsm::element {

InitialChord initial_chord(const Vector2& start, const Vector2& end) {
  const Vector2 delta = end - start;
  return {start, end, delta.norm(), direction_angle(delta.y(), delta.x())};  // as current_chord: β = 0 exactly at D = 0
}

double direction_angle(double y, double x) {
  // atan2 by the quadrant around atan of the smaller ratio (|ratio| ≤ 1 keeps atan's accuracy):
  // within an ulp of std::atan2 and cheaper, as glibc's atan2 saves and restores the rounding
  // mode on every call (bench/README.md).
  constexpr double pi = std::numbers::pi, half_pi = pi / 2;
  if (std::abs(x) >= std::abs(y)) {
    const double a = std::atan(y / x);
    return !std::signbit(x) ? a : (!std::signbit(y) ? a + pi : a - pi);
  }
  const double a = std::atan(x / y);
  return !std::signbit(y) ? half_pi - a : -half_pi - a;
}

double wrap_angle(double angle) {
  constexpr double two_pi = 2.0 * std::numbers::pi;
  constexpr double turns_per_radian = 1.0 / two_pi;
  return angle - two_pi * std::nearbyint(angle * turns_per_radian);
}

Chord current_chord(const InitialChord& initial, const Vector6& d, double previous_rotation) {
  const Vector2 delta0 = initial.end - initial.start;
  const Vector2 relative(d[3] - d[0], d[4] - d[1]);
  const Vector2 delta = delta0 + relative;
  Chord chord;
  chord.length = delta.norm();
  // l² − l0² = (2Δ0 + Δu)·Δu, so δl keeps its digits when it is tiny against l0.
  chord.elongation = (2.0 * delta0 + relative).dot(relative) / (chord.length + initial.length);
  const double inverse = 1.0 / chord.length;
  chord.cos = delta.x() * inverse;
  chord.sin = delta.y() * inverse;
  const double angle = direction_angle(delta.y(), delta.x());
  chord.rotation = previous_rotation + wrap_angle(angle - initial.angle - previous_rotation);
  return chord;
}

EquilibriumMatrix equilibrium_matrix(const Chord& chord) {
  const double c = chord.cos, s = chord.sin, l = chord.length;
  EquilibriumMatrix J;
  J << -c, -s / l, -s / l,  //
      -s, c / l, c / l,     //
      0.0, 1.0, 0.0,        //
      c, s / l, s / l,      //
      s, -c / l, -c / l,    //
      0.0, 0.0, 1.0;
  return J;
}

Matrix6 geometric_stiffness(const Chord& chord, const Eigen::Vector3d& forces) {
  const double c = chord.cos, s = chord.sin, l = chord.length;
  Vector6 z, r;
  z << s, -c, 0.0, -s, c, 0.0;
  r << -c, -s, 0.0, c, s, 0.0;
  const double N = forces[0], moment_sum = forces[1] + forces[2];
  return (N / l) * z * z.transpose() + (moment_sum / (l * l)) * (r * z.transpose() + z * r.transpose());
}

ChordPlace place_on_chord(const Vector2& a, const Vector2& b, const Vector2& x) {
  const Vector2 chord = b - a, r = x - a;
  const double length2 = chord.squaredNorm();
  if (!(length2 > 0.0)) return {};
  return {r.dot(chord) / length2, (chord.x() * r.y() - chord.y() * r.x()) / std::sqrt(length2)};
}

double alpha_on_chord(const Vector2& a, const Vector2& b, const Vector2& x) {
  const Vector2 chord = b - a, r = x - a;
  const double length2 = chord.squaredNorm();
  return length2 > 0.0 ? r.dot(chord) / length2 : 0.0;
}

double distance_to_segment(const Vector2& a, const Vector2& b, const Vector2& x) {
  const double length2 = (b - a).squaredNorm();
  const double t = length2 > 0.0 ? std::clamp((x - a).dot(b - a) / length2, 0.0, 1.0) : 0.0;
  return (a + t * (b - a) - x).norm();
}

ChordFrame chord_frame(const InitialChord& initial, const Vector6& d) {
  // The chord's length and direction as current_chord forms them.
  const Vector2 delta = (initial.end - initial.start) + Vector2(d[3] - d[0], d[4] - d[1]);
  ChordFrame frame;
  frame.length = delta.norm();
  const double inverse = 1.0 / frame.length;
  frame.e = Vector2(delta.x() * inverse, delta.y() * inverse);
  frame.start = initial.start + d.head<2>();
  return frame;
}

}  // namespace tsm::element
