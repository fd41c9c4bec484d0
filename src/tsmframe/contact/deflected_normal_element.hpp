#pragma once
// The three-node contact element with the contact force normal to the element's deflected shape
// at the contact point (docs/contact-normal.md, N1–N15; issue 27 part 2), instead of normal to its
// chord (the paper's Eq. 6–9, contact_element.hpp). Pure and local, like chord_frame_response.
//
// α, δy_c and the forces S = (N, M_i, M_j, Y) are the paper's element's, measured along the
// chord's normal n as today (§4 of the note: with the shape held, that measure's level lines run
// along the deflected shape, so its gradient is the deflected normal). What changes is where Y
// goes: the force on the contact node is Y ν, ν = n − w' e, w' = w_α / l the slope of the shape
//     w(s) = −h(s)ᵀ θ_e + G(s, α) Y   (the free shape of the element's own end rotations θ_e plus
//                                     the point load's own deflection, N1)
// at s = α — the mean of its two one-sided slopes where a Timoshenko beam's shear kinks it (N2). Y is
// still the force's share along n (the law's), −w' Y its share along e, which splits the axial
// force at the point (N6). In the nodal forces this is the chord element's less T ∂α/∂x, T = Y w_α
// (N7, N8), and it is exactly the chord element where w_α = 0.
//
// Used where a contact asks for "normal": "deflected" (contact_response.cpp), one point per element.

#include <Eigen/Core>

#include "tsmframe/contact/contact_element.hpp"

namespace tsm::contact {

/// What the shape's slope at the point needs of the beam with its ends held (no floor, no end
/// connections), at s = α clamped to [0, 1]: h's and c's first and second α-derivatives (N2, N12).
struct ShapeSlopeTerms {
  Eigen::Vector2d dh = Eigen::Vector2d::Zero();   ///< dh/dα = −dN/ds (the free shape's slope per unit θ, negated)
  Eigen::Vector2d ddh = Eigen::Vector2d::Zero();  ///< d²h/dα² (0 outside [0, 1])
  double dc = 0.0;   ///< dc/dα: twice the mean slope of the point load's own deflection per unit Y
  double ddc = 0.0;  ///< d²c/dα² (0 outside [0, 1])
};
ShapeSlopeTerms shape_slope_terms(const element::SectionStiffness& section, double l0, double alpha);

/// ∂α/∂x of a contact node at α, its distance ρ = r·n from the chord, on the translations of
/// i, j, c (N10, FORMULATION §2), and ∂²α/∂x² (N11); shared with the k-point element.
Vector9 alpha_gradient(const element::Chord& chord, double alpha, double rho);
Matrix9 alpha_hessian(const element::Chord& chord, double alpha, double rho);
/// K += scale · ∂²α/∂x², without forming it apart.
void add_alpha_hessian(Matrix9& K, double scale, const element::Chord& chord, double alpha, double rho);

/// The deflected normal at the contact point of a state (N2–N6).
struct DeflectedNormal {
  double slope = 0.0;  ///< w' = w_α / l: the shape's (mean) slope at α against the current chord
  Eigen::Vector2d direction = Eigen::Vector2d::Zero();  ///< ν = n − w' e: the force on the contact node is Y ν
  double axial_share = 0.0;  ///< −w' Y: the force on the beam at the point along e
  /// The axial force on either side of the point: between node i and the point, N + (1 − α)(−w' Y);
  /// between the point and node j, N − α(−w' Y). N = EA δl / l0 is their length-weighted mean.
  double axial_force_i = 0.0, axial_force_j = 0.0;
};
/// For a response of deflected_normal_response (or chord_frame_response: the same α, δy_c and S).
DeflectedNormal deflected_normal(const ContactElementData& data, const ContactResponse& response);

/// The bent shape's slope at the point, w_α (N2), and with `with_gradient` its gradient ∇w_α on
/// the element's dofs (N13), for a response of either normal (the same α, δy_c and S).
struct ShapeSlopeAt {
  double w_alpha = 0.0;
  Vector9 gradient = Vector9::Zero();
};
ShapeSlopeAt shape_slope_at(const ContactElementData& data, const ContactResponse& response, bool with_gradient);

/// The element in the chord frame with the force along the deflected normal (`data.frame` is not
/// read). d = (u_i, v_i, Θ_i, u_j, v_j, Θ_j, u_c, v_c, Θ_c); Θ_c plays no part. The fields are
/// chord_frame_response's, with what they mean now (N14, N15):
/// - chord, alpha, normal, deformations, forces: the same (Y: the force's share along n);
/// - nodal_forces: J_ν S, the force on c being Y ν;
/// - point_u = J_ν (0, h_i, h_j, 1)ᵀ: the point load's nodal forces per unit Y along the deflected
///   normal; point_stiffness = 1/c. point_u point_uᵀ/c is in symmetric_tangent; what Y's gradient
///   has beyond point_u/c lies along ∂α/∂x and is in the sliding term (Newton's look-ahead of a
///   release leaves it out, as it leaves out the sliding term today);
/// - tangent = ∂(J_ν S)/∂D = symmetric_tangent + sliding_u sliding_vᵀ, sliding_v = ∂α/∂x as
///   today. The turning of ν with θ, δy_c and α is non-symmetric with ∂α/∂x on the left; its
///   symmetric completion is in symmetric_tangent and the rest joins the sliding term, so the
///   tangent keeps today's form (a symmetric part and one rank-one term). Without the sliding term
///   (data.sliding_term false) tangent = symmetric_tangent, a quasi-Newton tangent.
ContactResponse deflected_normal_response(const ContactElementData& data, const Vector9& d, double previous_rotation,
                                          bool with_tangent = true);

}  // namespace tsm::contact
