#pragma once
// The three-node contact element (FORMULATION §2): beam element i–j with contact node c.
// Strict compatibility from current coordinates, like the two-node element:
//     α = (r·e)/l,  δy_c = r·n − offset,  r = x_c − x_i,
// forces S = (N, M_i, M_j, Y) from contact_force_law at the current α, nodal forces J S
// (9×4 equilibrium matrix; the force on c is Y n) and the consistent tangent
//     K = J (∂S/∂d) Jᵀ + K_G + J (∂S/∂α)(∂α/∂x)ᵀ,
// the last (sliding) term non-symmetric; it can be left out (a quasi-Newton tangent).

#include <Eigen/Core>

#include "tsmframe/contact/contact_force_law.hpp"
#include "tsmframe/contact/friction.hpp"
#include "tsmframe/element/chord.hpp"
#include "tsmframe/model/model.hpp"

namespace tsm::contact {

using Vector4 = Eigen::Matrix<double, 4, 1>;
using Vector9 = Eigen::Matrix<double, 9, 1>;

/// The translational part of a 9-vector (rows u, v of nodes i, j, c) from three plane vectors.
inline Vector9 spread(const Eigen::Vector2d& at_i, const Eigen::Vector2d& at_j, const Eigen::Vector2d& at_c) {
  Vector9 v = Vector9::Zero();
  v.segment<2>(0) = at_i;
  v.segment<2>(3) = at_j;
  v.segment<2>(6) = at_c;
  return v;
}
using Matrix9 = Eigen::Matrix<double, 9, 9>;

/// K += x yᵀ + y xᵀ: the symmetric outer products the contact tangents are sums of.
inline void add_symmetric(Matrix9& K, const Vector9& x, const Vector9& y) {
  K.noalias() += x * y.transpose();
  K.noalias() += y * x.transpose();
}
using ContactEquilibriumMatrix = Eigen::Matrix<double, 9, 4>;  // rows i, j, c × (u, v, θ)

/// What does not change while a contact sits on one element.
struct ContactElementData {
  element::InitialChord initial;      ///< the beam element's chord as drawn
  element::SectionStiffness section;  ///< EA, EI and Ψ (Ψ = 0: Euler–Bernoulli, Eq. 6)
  element::Matrix3 k0;                ///< the plain element's k0 (Eq. 3 / 4) with this section
  Eigen::Vector2d contact_start;      ///< X_c, the contact node as drawn
  double offset = 0.0;                ///< δy_c at which Y = 0 on a straight beam (side · gap)
  double edge = 1e-2;                 ///< compliance clamp, see point_load_law
  double min_compliance = 0.0;        ///< the stiffness cap's compliance floor (0: none), see point_load_law
  bool sliding_term = true;           ///< include J (∂S/∂α)(∂α/∂x)ᵀ in the tangent
  ContactFrame frame = ContactFrame::chord;  ///< the chord's (Eq. 6–9) or the cantilever's (FORMULATION §2b; contact_response.hpp)
  ContactNormal normal = ContactNormal::chord;  ///< chord frame: the force along the chord's normal or the bent beam's
  /// How the element's ends are joined to its nodes: 0 rigidly, ∞ by a hinge (a member's
  /// "release"), 1/k by a rotational spring ("end_springs"); see connected_law. Chord frame only.
  double flexibility_i = 0.0, flexibility_j = 0.0;
  FrictionData friction;  ///< Coulomb friction at the point (μ = 0: none; friction.hpp)
  bool connected() const { return flexibility_i != 0.0 || flexibility_j != 0.0; }
};

/// The law at α as the chord frame evaluates it: the beam's own (raw) and, where the ends are
/// hinged or sprung, the connected one (connected_law; the raw one where they are rigid), with the
/// bending block that goes with it.
struct ChordFrameLaw {
  PointLoadLaw raw, connected;
  Eigen::Matrix2d k_plain = Eigen::Matrix2d::Zero();
};
ChordFrameLaw chord_frame_law(const ContactElementData& data, double alpha);

struct ContactResponse {
  element::Chord chord;
  ChordFrameLaw law;      ///< the law at α the forces were formed with (chord frame)
  double alpha = 0.0;     ///< α = l_ic / l on the current chord (may leave [0, 1]: hand over)
  double normal = 0.0;    ///< r·n, the contact node's distance from the chord
  Vector4 deformations;   ///< (δl, θ_i, θ_j, δy_c)
  Vector4 forces;         ///< S = (N, M_i, M_j, Y)
  Vector9 nodal_forces;   ///< J S
  /// The point load's direction and stiffness: Y acts on the nodes as Y · point_u (point_u =
  /// J (0, h_i, h_j, 1)ᵀ), and its stiffness part is point_stiffness · point_u point_uᵀ with
  /// point_stiffness = 1/c — what letting go of the contact takes out (Newton's look-ahead).
  Vector9 point_u = Vector9::Zero();
  double point_stiffness = 0.0;
  /// |force on c| / |Y|: 1 along the chord's normal, |ν| = √(1 + w'²) along the bent beam's.
  double force_per_Y = 1.0;
  Matrix9 tangent;        ///< ∂(J S)/∂D (when asked for) = symmetric_tangent + sliding_u sliding_vᵀ
  Matrix9 symmetric_tangent;  ///< J (∂S/∂d) Jᵀ + K_G
  Vector9 sliding_u = Vector9::Zero();  ///< the sliding term is the rank-one u vᵀ: u = J ∂S/∂α …
  Vector9 sliding_v = Vector9::Zero();  ///< … v = ∂α/∂x (both zero without the sliding term)
  /// Friction (friction.hpp; zero and `none` at μ = 0): tangent += friction_u friction_vᵀ.
  FrictionResult friction;
  Vector9 friction_u = Vector9::Zero(), friction_v = Vector9::Zero();
};

/// The element in the chord frame (Eq. 6–9; `data.frame` is not read here).
/// d = (u_i, v_i, Θ_i, u_j, v_j, Θ_j, u_c, v_c, Θ_c); Θ_c plays no part.
ContactResponse chord_frame_response(const ContactElementData& data, const Vector9& d, double previous_rotation,
                                     bool with_tangent = true);
/// The same without its last sum: `tangent` is left unset, symmetric_tangent and the sliding
/// term formed — what the element with the force along the bent beam's normal builds on.
ContactResponse chord_frame_parts(const ContactElementData& data, const Vector9& d, double previous_rotation,
                                  bool with_tangent);

/// J (9×4): columns N, M_i, M_j as for the two-node element, Y: i −(1−α) n, j −α n, c +n.
ContactEquilibriumMatrix contact_equilibrium_matrix(const element::Chord& chord, double alpha);

/// Where a node sits relative to a beam element that carries no contact, from the element's
/// own state: α along the chord and the signed distance from the element's deflected centre
/// line there, gap = r·n − w(α) (w: the deflection at which a contact force would be zero).
struct NodeOnElement {
  double alpha = 0.0;
  double gap = 0.0;
};
/// node_on_element's α alone (the same arithmetic, without the chord's rotation or the free
/// shape): what rules an element out before its gap is worth measuring.
double alpha_on_element(const element::InitialChord& initial, const element::Vector6& element_displacements,
                        const Eigen::Vector2d& node_position);
NodeOnElement node_on_element(const element::InitialChord& initial, const element::SectionStiffness& section,
                              const element::Vector6& element_displacements, double chord_rotation,
                              const Eigen::Vector2d& node_position, double flexibility_i = 0.0,
                              double flexibility_j = 0.0);

}  // namespace tsm::contact
