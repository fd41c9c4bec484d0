#pragma once
// Kinematics of the element chord (FORMULATION §1): current length and direction, the chord
// rotation tracked continuously, the equilibrium matrix J and the geometric stiffness K_G.
// Pure functions of coordinates; no material data.

#include <Eigen/Core>

namespace tsm::element {

using Vector2 = Eigen::Vector2d;
using Vector6 = Eigen::Matrix<double, 6, 1>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;
using EquilibriumMatrix = Eigen::Matrix<double, 6, 3>;  // rows u_i v_i θ_i u_j v_j θ_j; cols N M_i M_j

/// The element as first drawn: end positions, from which l0 and φ0 follow.
struct InitialChord {
  Vector2 start;  ///< X_i
  Vector2 end;    ///< X_j
  double length = 0.0;  ///< l0
  double angle = 0.0;   ///< φ0
};
InitialChord initial_chord(const Vector2& start, const Vector2& end);

/// The chord in the current configuration.
struct Chord {
  double length = 0.0;     ///< l
  double elongation = 0.0; ///< δl = l − l0, computed without cancellation
  double cos = 1.0;        ///< c = cos φ
  double sin = 0.0;        ///< s = sin φ
  double rotation = 0.0;   ///< β = φ − φ0, a true total (never wrapped)
};

/// The angle of the direction (x, y) in [−π, π], as std::atan2(y, x) gives it (within an ulp).
double direction_angle(double y, double x);

/// Angle wrapped into [−π, π].
double wrap_angle(double angle);

/// Current chord from the end displacements (u_i, v_i, u_j, v_j are d[0], d[1], d[3], d[4]).
/// The rotation continues `previous_rotation` by the smallest turn (FORMULATION §1).
Chord current_chord(const InitialChord& initial, const Vector6& d, double previous_rotation);

/// J: nodal forces = J · (N, M_i, M_j) (Eq. 1).
EquilibriumMatrix equilibrium_matrix(const Chord& chord);

/// K_G = (N/l) z zᵀ + ((M_i + M_j)/l²)(r zᵀ + z rᵀ) (FORMULATION §1; the δJ·S term of Eq. 2).
Matrix6 geometric_stiffness(const Chord& chord, const Eigen::Vector3d& forces);

// ---- A point against a straight chord (contact detection, resting contacts, the ordering)

/// Point x in the frame of the straight chord a → b: α along it (0 at a, 1 at b) and the signed
/// distance across it (along n, the chord's direction turned +90°). {0, 0} for a zero chord.
struct ChordPlace {
  double alpha = 0.0;
  double across = 0.0;
};
ChordPlace place_on_chord(const Vector2& a, const Vector2& b, const Vector2& x);
/// place_on_chord's α alone (the same arithmetic, no square root).
double alpha_on_chord(const Vector2& a, const Vector2& b, const Vector2& x);
/// The distance from x to the segment a–b (to its nearer end beyond it).
double distance_to_segment(const Vector2& a, const Vector2& b, const Vector2& x);

/// An element's current chord as α needs it: its start X_i + u_i, unit direction e and length
/// (current_chord's arithmetic).
struct ChordFrame {
  Vector2 start, e;
  double length = 0.0;
  /// α of a point on this chord, (x − x_i)·e / l.
  double alpha(const Vector2& point) const { return (point - start).dot(e) / length; }
};
ChordFrame chord_frame(const InitialChord& initial, const Vector6& element_displacements);

}  // namespace tsm::element
