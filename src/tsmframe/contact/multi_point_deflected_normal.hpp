#pragma once
// The contact element with k interior points and each contact force along the normal of the
// element's deflected shape at its point (docs/contact-normal.md §8, N16–N21; issue 27 part 2 for
// several points per element), instead of along the chord's normal (multi_point_element.hpp). It is
// to multi_point_response what deflected_normal_response is to chord_frame_response, and equals
// that for k = 1.
//
// α_p, δy_p and S = (N, M_i, M_j, Y_1 … Y_k) are multi_point_response's, measured along the
// chord's normal n (§4 of the note). The force on contact node c_p is Y_p ν_p, ν_p = n − w'_p e,
// w'_p = w_α,p / l the slope at α_p of the shape
//     w(s) = −h(s)ᵀ θ_e + Σ_q G(s, α_q) Y_q       (the element's own end rotations θ_e and every
//                                                 point's load on the clamped beam, N1 summed)
// — the mean of its one-sided slopes at α_p, where a Timoshenko beam's shear kinks it under Y_p
// (N16). The beam's own law is read without the compliance floors (§1, "Where the direction is
// read"), and beyond an element end a point's direction is held at the end's. The nodal forces are
// multi_point_response's less Σ_p T_p ∂α_p/∂x, T_p = Y_p w_α,p (N18).
// A point whose ContactPointData::normal is the chord's keeps its force along n (its w_α held at
// 0), so points of both kinds may share an element. Used by active_contact.cpp for k ≥ 2.

#include <Eigen/Core>

#include "tsmframe/contact/multi_point_element.hpp"

namespace tsm::contact {

/// The slopes w_α,p (per unit α, against the current chord) of the element's deflected shape at
/// its points (N16), for a response of multi_point_response or multi_point_deflected_response (the
/// same α, δy and S). w'_p = w_α,p / l.
Eigen::VectorXd multi_point_shape_slopes(const MultiPointElementData& data, const MultiPointResponse& response);

/// The element with the forces along the deflected normals. d as for multi_point_response. The
/// fields are multi_point_response's, with what they mean now (N18–N21):
/// - chord, alpha, normal, deformations, forces, point_stiffness: the same (Y_p: the share of the
///   force on c_p along n);
/// - nodal_forces: J S − Σ_p T_p ∂α_p/∂x, the force on c_p being Y_p ν_p;
/// - force_per_Y: |ν_p| = √(1 + w'_p²);
/// - point_u: column p = J P e_p − w_α,p ∂α_p/∂x, point p's load along its deflected normal per
///   unit Y_p; point_u · point_stiffness · point_uᵀ is in symmetric_tangent;
/// - tangent = ∂(nodal_forces)/∂D = symmetric_tangent + Σ_p sliding_u.col(p) sliding_v.col(p)ᵀ,
///   sliding_v.col(p) = ∂α_p/∂x as for the chord's normal. Each point's normal turns with every
///   point's Y_q and α_q and with θ; that turning has ∂α_p/∂x on the left, its symmetric
///   completion is in symmetric_tangent and the rest joins point p's sliding term (N21). Without
///   the sliding terms (data.sliding_term false) tangent = symmetric_tangent.
MultiPointResponse multi_point_deflected_response(const MultiPointElementData& data, const Eigen::VectorXd& d,
                                                  double previous_rotation, bool with_tangent = true);

}  // namespace tsm::contact
