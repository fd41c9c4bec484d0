#include "tsmframe/element/beam_element.hpp"

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

}  // namespace tsm::element
