#pragma once
// The contact element with k interior points in the cantilever frame (FORMULATION §2b for one
// point; docs/contact-k-points.md §9): beam element i–j with contact nodes c_1 … c_k, in a frame
// clamped at node i's current rotation, ψ = φ0 + Θ_i, t = (cos ψ, sin ψ), m = t turned +90°:
//     d = (u, v_j, θ_j, v_1 … v_k) = (r_j·t − l0, r_j·m, Θ_j − Θ_i, r_p·m − offset_p),
//     α_p = (r_p·t)/(r_j·t),  r = x − x_i.
// The law is the chord frame's k-point law with the cantilever's end forces in place of the
// fixed-end moments: C Y = v + Gᵀ (v_j, θ_j), (Q, M) = k_cantilever (v_j, θ_j) + G Y, with C the
// points' clamped–clamped compliance (multi_point_law's, floors included) and G's column p
// §2b's load share at α_p. Each force Y_p acts on the beam along +m at c_p and is carried to node
// i (no lever rule). k = 1 is cantilever_frame_response value for value.

#include <Eigen/Core>

#include "tsmframe/contact/multi_point_element.hpp"

namespace tsm::contact {

/// The element in the cantilever frame (`data` as for multi_point_response; its end releases
/// and springs are not read: such members carry no cantilever-frame contact). The response's
/// forces are reported in the chord frame (N, M_i, M_j from the nodal forces, then Y_1 … Y_k).
MultiPointResponse multi_point_cantilever_response(const MultiPointElementData& data, const Eigen::VectorXd& d,
                                                   double previous_rotation, bool with_tangent = true);

}  // namespace tsm::contact
