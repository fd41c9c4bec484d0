#include "tsmframe/element/beam_element.hpp"

#include <cmath>
#include <limits>

namespace tsm::element {

BeamResponse beam_response(const InitialChord& initial, const SectionStiffness& section,
                           const Vector6& d, double previous_rotation, bool with_tangent) {
  BeamResponse r;
  r.chord = current_chord(initial, d, previous_rotation);
  // Strict compatibility: θ = Θ − β at both ends (FORMULATION §1).
  r.deformations = {r.chord.elongation, d[2] - r.chord.rotation, d[5] - r.chord.rotation};
  const Matrix3 k0 = basic_stiffness(section, initial.length);
  r.forces = k0 * r.deformations;  // Eq. 3 / Eq. 4
  const EquilibriumMatrix J = equilibrium_matrix(r.chord);
  r.nodal_forces = J * r.forces;  // Eq. 1
  if (with_tangent) r.tangent = J * k0 * J.transpose() + geometric_stiffness(r.chord, r.forces);  // Eq. 2
  return r;
}

RoundOffFloor round_off_floor(const InitialChord& initial, const SectionStiffness& section, const Vector6& d,
                              const BeamResponse& response) {
  constexpr double eps = std::numeric_limits<double>::epsilon();
  const double l0 = initial.length, l = response.chord.length;
  const Matrix3 k0 = basic_stiffness(section, l0);
  // δl and β come from Δ0 + (u_j − u_i): an absolute error of about ε(|u_i| + |u_j| + l0).
  const double length_error = eps * (std::abs(d[0]) + std::abs(d[1]) + std::abs(d[3]) + std::abs(d[4]) + l0);
  const double chord_angle_error = length_error / l + eps * std::abs(response.chord.rotation);
  // A chord-angle error turns θ_i and θ_j alike: M_i, M_j change by the row sums of k0.
  const double moment_i = std::abs(k0(1, 1) + k0(1, 2)) * chord_angle_error + eps * (k0(1, 1) * std::abs(d[2]) + std::abs(k0(1, 2) * d[5]));
  const double moment_j = std::abs(k0(2, 1) + k0(2, 2)) * chord_angle_error + eps * (std::abs(k0(2, 1) * d[2]) + k0(2, 2) * std::abs(d[5]));
  RoundOffFloor floor;
  floor.moment = std::max(moment_i, moment_j) + eps * response.forces.tail<2>().cwiseAbs().maxCoeff();
  floor.force = k0(0, 0) * length_error + (moment_i + moment_j) / l + eps * response.forces.cwiseAbs().maxCoeff();
  return floor;
}

}  // namespace tsm::element
