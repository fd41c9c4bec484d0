#pragma once
// The "cantilever coordinate" contact element (FORMULATION §2b; the paper names it, Fig. 7):
// beam element i–j with contact node c, in a frame clamped at node i's current rotation,
// ψ = φ0 + Θ_i, t = (cos ψ, sin ψ), m = t turned +90°:
//     d = (u, v_j, θ_j, v_c) = (r_j·t − l0, r_j·m, Θ_j − Θ_i, r_c·m − offset),  α = s_c / s_j,
// S = (N, Q, M, Y): axial and transverse force at j, moment at j, and the contact force on the
// beam along +m at c. Like the chord element, the force law is used split into the plain
// cantilever plus a point load — Y = (v_c + g·(v_j, θ_j)) / c, (Q, M) = k_cantilever (v_j, θ_j) + g Y
// — an exact rearrangement of §2b's matrix whose compliance c is the chord element's (and is
// floored the same way near the element ends).

#include "tsmframe/contact/contact_element.hpp"

namespace tsm::contact {

/// The fixed-end forces at j per unit point force Y at α on the element clamped at both ends,
/// in the cantilever frame: g = (K(Q,Y), K(M,Y)) / K(Y,Y) of §2b (its factor EI/Ω cancels), and
/// their α-derivatives (0 outside [0, 1], where g holds α clamped). ψ: the section's Ψ.
struct LoadShare {
  double q = 0.0, m = 0.0, dq = 0.0, dm = 0.0;
};
LoadShare cantilever_load_share(double psi, double l0, double alpha);

/// §2b's bending block (v_j, θ_j, v_c) → (Q, M, Y) at α, as FORMULATION writes it (0 < α < 1).
element::Matrix3 cantilever_bending_stiffness(const element::SectionStiffness& section, double l0, double alpha);

/// The plain cantilever (no contact): (v_j, θ_j) → (Q, M).
Eigen::Matrix2d cantilever_stiffness(const element::SectionStiffness& section, double l0);

/// The three-node element in the cantilever frame (`data.frame` is not read here).
/// The response's forces are reported in the chord frame (N, M_i, M_j from the nodal forces, Y).
ContactResponse cantilever_frame_response(const ContactElementData& data, const Vector9& d, double previous_rotation,
                                          bool with_tangent = true);

}  // namespace tsm::contact
