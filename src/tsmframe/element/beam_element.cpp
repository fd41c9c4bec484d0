#include "tsmframe/element/beam_element.hpp"

#include <cmath>
#include <limits>

namespace tsm::element {

namespace {

// One body for both forms of k0: Stiffness gives k0(a, b).
template <class Stiffness>
BeamResponse response_of(const InitialChord& initial, const Stiffness& k0, const Vector6& d,
                         double previous_rotation, bool with_tangent) {
  BeamResponse r;
  r.chord = current_chord(initial, d, previous_rotation);
  const double c = r.chord.cos, s = r.chord.sin, l = r.chord.length;
  // Strict compatibility: θ = Θ − β at both ends (FORMULATION §1).
  r.deformations = {r.chord.elongation, d[2] - r.chord.rotation, d[5] - r.chord.rotation};
  for (int a = 0; a < 3; ++a)  // S = k0 d (Eq. 3 / Eq. 4)
    r.forces[a] = k0(a, 0) * r.deformations[0] + k0(a, 1) * r.deformations[1] + k0(a, 2) * r.deformations[2];
  const double N = r.forces[0], Mi = r.forces[1], Mj = r.forces[2];
  // J S (Eq. 1): along the chord u = (c, s) and across it n = (−s, c).
  const double inverse = 1.0 / l;
  const double shear = (Mi + Mj) * inverse;
  const double fx = -N * c - shear * s, fy = -N * s + shear * c;
  r.nodal_forces << fx, fy, Mi, -fx, -fy, Mj;
  if (!with_tangent) return r;
  // J k0 Jᵀ + K_G (Eq. 2): translations couple through P = EA/l0 u uᵀ + (Σk/l² + N/l) n nᵀ
  // + (M_i + M_j)/l² (u nᵀ + n uᵀ), rotations through (k_ii + k_ij)/l n and (k_ij + k_jj)/l n.
  const double axial = k0(0, 0), transverse = (k0(1, 1) + 2.0 * k0(1, 2) + k0(2, 2)) * inverse * inverse + N * inverse;
  const double mixed = shear * inverse;
  const double pxx = axial * c * c + transverse * s * s - 2.0 * mixed * c * s;
  const double pyy = axial * s * s + transverse * c * c + 2.0 * mixed * c * s;
  const double pxy = (axial - transverse) * c * s + mixed * (c * c - s * s);
  const double qi = (k0(1, 1) + k0(1, 2)) * inverse, qj = (k0(1, 2) + k0(2, 2)) * inverse;
  Matrix6& K = r.tangent;
  K << pxx, pxy, -qi * s, -pxx, -pxy, -qj * s,  //
      pxy, pyy, qi * c, -pxy, -pyy, qj * c,     //
      -qi * s, qi * c, k0(1, 1), qi * s, -qi * c, k0(1, 2),  //
      -pxx, -pxy, qi * s, pxx, pxy, qj * s,     //
      -pxy, -pyy, -qi * c, pxy, pyy, -qj * c,   //
      -qj * s, qj * c, k0(2, 1), qj * s, -qj * c, k0(2, 2);
  return r;
}

}  // namespace

BeamResponse beam_response(const InitialChord& initial, const Matrix3& k0, const Vector6& d,
                           double previous_rotation, bool with_tangent) {
  return response_of(initial, k0, d, previous_rotation, with_tangent);
}

BeamResponse beam_response(const InitialChord& initial, const BasicStiffness& k0, const Vector6& d,
                           double previous_rotation, bool with_tangent) {
  return response_of(initial, k0, d, previous_rotation, with_tangent);
}

RoundOffFloor round_off_floor(const InitialChord& initial, const Matrix3& k0, const Vector6& d,
                              const BeamResponse& response) {
  constexpr double eps = std::numeric_limits<double>::epsilon();
  const double l0 = initial.length, l = response.chord.length;
  // δl and β come from Δ0 + (u_j − u_i): an absolute error of about ε(|u_i| + |u_j| + l0).
  const double length_error = eps * (std::abs(d[0]) + std::abs(d[1]) + std::abs(d[3]) + std::abs(d[4]) + l0);
  // β = φ − φ0 from two angles up to π in size: ε of each (an inclined or curved member's
  // chords carry ~1e-15 rad of it; a ring moved rigidly was "carrying" its moments' rounding).
  const double chord_angle_error =
      length_error / l + eps * (std::abs(response.chord.rotation) + 2.0 * std::abs(initial.angle));
  // A chord-angle error turns θ_i and θ_j alike: M_i, M_j change by the row sums of k0.
  const double moment_i = std::abs(k0(1, 1) + k0(1, 2)) * chord_angle_error + eps * (k0(1, 1) * std::abs(d[2]) + std::abs(k0(1, 2) * d[5]));
  const double moment_j = std::abs(k0(2, 1) + k0(2, 2)) * chord_angle_error + eps * (std::abs(k0(2, 1) * d[2]) + k0(2, 2) * std::abs(d[5]));
  RoundOffFloor floor;
  floor.moment = std::max(moment_i, moment_j) + eps * response.forces.tail<2>().cwiseAbs().maxCoeff();
  floor.force = k0(0, 0) * length_error + (moment_i + moment_j) / l + eps * response.forces.cwiseAbs().maxCoeff();
  return floor;
}

}  // namespace tsm::element
