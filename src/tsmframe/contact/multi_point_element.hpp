#pragma once
// The contact element with k interior points in the chord frame (docs/contact-k-points.md §7;
// issue 27): beam element i–j with contact nodes c_1 … c_k. Strict compatibility from current
// coordinates, as chord_frame_response (which it equals for k = 1):
//     α_p = (r_p·e)/l,  δy_p = r_p·n − offset_p,  r_p = x_{c_p} − x_i,
// forces S = (N, M_i, M_j, Y_1 … Y_k) from multi_point_law (K2), nodal forces J S (the force on
// c_p is Y_p n) and the consistent tangent (K15)
//     K = J (∂S/∂d) Jᵀ + K_G + Σ_p J (∂S/∂α_p)(∂α_p/∂x)ᵀ,
// each point's sliding term a rank-one term kept apart, so a solver can leave them out.
// Used for every element with two or more contact points (active_contact.cpp).

#include <vector>

#include <Eigen/Core>

#include "tsmframe/contact/friction.hpp"
#include "tsmframe/contact/multi_point_law.hpp"
#include "tsmframe/element/chord.hpp"
#include "tsmframe/element/force_law.hpp"
#include "tsmframe/model/model.hpp"

namespace tsm::contact {

/// One contact node on the element, as drawn.
struct ContactPointData {
  Eigen::Vector2d start = Eigen::Vector2d::Zero();  ///< X_c, the contact node as drawn
  double offset = 0.0;  ///< δy at which Y = 0 on a straight beam (side · gap)
  /// The normal its force acts along: the chord's (this element) or the bent beam's
  /// (multi_point_deflected_normal.hpp, which keeps a chord point's force along the chord's).
  ContactNormal normal = ContactNormal::chord;
  FrictionData friction;  ///< Coulomb friction at the point (μ = 0: none; friction.hpp)
};

/// What does not change while the contacts sit on one element (ContactElementData for k points).
struct MultiPointElementData {
  element::InitialChord initial;      ///< the beam element's chord as drawn
  element::SectionStiffness section;  ///< EA, EI and Ψ (Ψ = 0: Euler–Bernoulli)
  element::Matrix3 k0;                ///< the plain element's k0 (Eq. 3 / 4) with this section
  std::vector<ContactPointData> points;  ///< k ≥ 0 contact nodes
  double edge = 1e-2;                 ///< compliance floor near a node and between points (K10, K11)
  double min_compliance = 0.0;        ///< the stiffness cap's compliance floor (0: none)
  bool sliding_term = true;           ///< include Σ_p J (∂S/∂α_p)(∂α_p/∂x)ᵀ in the tangent
  /// The frame the element is written in (active_contact_response dispatches on it; the
  /// elements themselves do not read it).
  ContactFrame frame = ContactFrame::chord;
  /// How the element's ends are joined to its nodes: 0 rigidly, ∞ by a hinge, 1/k by a
  /// rotational spring (K12a, K12b).
  double flexibility_i = 0.0, flexibility_j = 0.0;
  bool connected() const { return flexibility_i != 0.0 || flexibility_j != 0.0; }
  int size() const { return static_cast<int>(points.size()); }
};

/// Rows: 3 per node, i, j, c_1 … c_k, each (u, v, θ); n = 3(2 + k).
struct MultiPointResponse {
  element::Chord chord;
  Eigen::VectorXd alpha;         ///< α_p on the current chord (may leave [0, 1]: hand over)
  Eigen::VectorXd normal;        ///< r_p·n, each contact node's distance from the chord
  Eigen::VectorXd deformations;  ///< (δl, θ_i, θ_j, δy_1 … δy_k)
  Eigen::VectorXd forces;        ///< S = (N, M_i, M_j, Y_1 … Y_k)
  Eigen::VectorXd nodal_forces;  ///< J S
  /// |force on c_p| / |Y_p|: 1 along the chord's normal, |ν| = √(1 + w'²) along the bent beam's
  /// (deflected_normal_element.hpp).
  Eigen::VectorXd force_per_Y;
  /// The point loads' directions and stiffness: Y_p acts on the nodes as Y_p · point_u.col(p)
  /// (= J (0, h_p, e_p)), and the points' stiffness part is point_u · point_stiffness · point_uᵀ
  /// with point_stiffness = C⁻¹ (k×k, not diagonal: the points are coupled through the beam).
  Eigen::MatrixXd point_u;
  Eigen::MatrixXd point_stiffness;
  Eigen::MatrixXd tangent;            ///< ∂(J S)/∂D (when asked for) = symmetric_tangent + sliding_u sliding_vᵀ
  Eigen::MatrixXd symmetric_tangent;  ///< J (∂S/∂d) Jᵀ + K_G
  Eigen::MatrixXd sliding_u;  ///< column p: J ∂S/∂α_p — point p's sliding term is sliding_u.col(p) …
  Eigen::MatrixXd sliding_v;  ///< … sliding_v.col(p)ᵀ, with column p ∂α_p/∂x (both zero without the term)
  /// Friction per point (friction.hpp; empty without any): tangent += Σ_p friction_u.col(p) friction_v.col(p)ᵀ.
  std::vector<FrictionResult> friction;
  Eigen::MatrixXd friction_u, friction_v;
};

/// J (3(2+k) × (3+k)): columns N, M_i, M_j as for the two-node element; Y_p: node i −(1−α_p) n,
/// node j −α_p n, node c_p +n.
Eigen::MatrixXd multi_point_equilibrium_matrix(const element::Chord& chord, const Eigen::VectorXd& alpha);

/// The element in the chord frame. d = (u_i, v_i, Θ_i, u_j, v_j, Θ_j, then u, v, Θ of each
/// contact node); the contact nodes' Θ play no part.
MultiPointResponse multi_point_response(const MultiPointElementData& data, const Eigen::VectorXd& d,
                                        double previous_rotation, bool with_tangent = true);

}  // namespace tsm::contact
