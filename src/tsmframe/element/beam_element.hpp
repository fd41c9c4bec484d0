#pragma once
// The two-node TSM beam element: strict compatibility (deformations from current coordinates),
// the element force equation, and its tangent K = J k0 Jᵀ + K_G (Eq. 1–2).

#include "tsmframe/element/chord.hpp"
#include "tsmframe/element/force_law.hpp"

namespace tsm::element {

/// Everything one evaluation of an element yields.
struct BeamResponse {
  Chord chord;
  Vector3 deformations;  ///< (δl, θ_i, θ_j)
  Vector3 forces;        ///< S = (N, M_i, M_j), chord frame
  Vector6 nodal_forces;  ///< J S, global frame
  Matrix6 tangent;       ///< ∂(J S)/∂D
};

/// Evaluates the element with force law `k0` (basic_stiffness) at end displacements
/// d = (u_i, v_i, Θ_i, u_j, v_j, Θ_j). `previous_rotation` is the chord rotation of the previous
/// iterate (continuous tracking). The tangent is J k0 Jᵀ + K_G written out in closed form
/// (the same matrix as equilibrium_matrix and geometric_stiffness give, without the products).
BeamResponse beam_response(const InitialChord& initial, const Matrix3& k0, const Vector6& d,
                           double previous_rotation, bool with_tangent = true);
/// The same with k0 as an element keeps it: read where it lies, no Matrix3 written per call (a
/// 3×3 written with 8-byte stores and read back in pairs stalls on the store buffer).
BeamResponse beam_response(const InitialChord& initial, const BasicStiffness& k0, const Vector6& d,
                           double previous_rotation, bool with_tangent = true);

/// How large the element's nodal forces can be in error from rounding alone, at this state:
/// positions are X + u, so δl and β carry an absolute error ≈ ε(|u_i| + |u_j| + l0), and
/// rotations θ = Θ − β one of ≈ ε(|Θ| + |β|). The residual cannot fall much below these.
struct RoundOffFloor {
  double force = 0.0;   ///< on each translational dof
  double moment = 0.0;  ///< on each rotational dof
};
RoundOffFloor round_off_floor(const InitialChord& initial, const Matrix3& k0, const Vector6& d,
                              const BeamResponse& response);

}  // namespace tsm::element
