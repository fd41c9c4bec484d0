#pragma once
// Force equation of the three-node contact element (paper Eq. 6–9, corrected in FORMULATION §2):
// a simply supported beam in its chord frame with end moments and a transverse point force Y at
// a = α l0 from node i. Pure and local, like element/force_law.
//
// The solver uses the law split as "the plain element plus a point load":
//     Y = (δy_c + h_i θ_i + h_j θ_j) / c,     (M_i, M_j) = k_plain (θ_i, θ_j) + (h_i, h_j) Y,
// with h = k_θY / k_YY (the fixed-end moments of a unit point load, up to sign) and c = 1/k_YY
// (the point's compliance with both ends held). It is the same matrix as Eq. 6/7 — an exact
// rearrangement, unit-tested against it — but it shows where the ill-conditioning near an
// element end lives: only in c, which vanishes like b³ (Euler–Bernoulli) or b (Timoshenko).
// h and the beam's free shape −h·θ are smooth and vanish at both ends; h = −N, the element's own
// shape functions of its end rotations (element/deflected_shape), by Maxwell–Betti.

#include <array>

#include "tsmframe/element/force_law.hpp"

namespace tsm::contact {

/// The bending block (θ_i, θ_j, δy_c) → (M_i, M_j, Y) of Eq. 6 (Ψ = 0) or Eq. 7, as written in
/// FORMULATION §2 — the reference form; needs 0 < α < 1.
element::Matrix3 contact_bending_stiffness(const element::SectionStiffness& section, double l0, double alpha);

/// The point-load split of the law at contact position α, with α-derivatives.
struct PointLoadLaw {
  double h_i = 0.0, h_j = 0.0;  ///< M_i, M_j per unit Y with the end rotations held
  double compliance = 0.0;      ///< c = 1 / k_YY
  double dh_i = 0.0, dh_j = 0.0, dcompliance = 0.0;  ///< d/dα of the above (0 where clamped)
};

/// The law at α (h and c use α clamped to [0, 1]). The compliance never falls below that of
/// an Euler–Bernoulli point `edge`·l0 from a beam node, c_min = (δ(1−δ) l0)³ / 3EI, δ = edge —
/// FORMULATION §3's explicit rule for a contact at or next to a node. Euler–Bernoulli reaches
/// c_min at α = δ or 1 − δ; Timoshenko, whose c falls only like b/(G A_s), much closer to the
/// node (at b ≈ δ³ l0³/(3Ψ)), unless its shear flexibility Ψ is negligible. Nor below
/// `min_compliance`: the contact's stiffness cap (ContactSpec::max_stiffness_ratio), a floor of
/// the same kind wherever the point's own compliance falls below it.
PointLoadLaw point_load_law(const element::SectionStiffness& section, double l0, double alpha, double edge,
                            double min_compliance = 0.0);
/// Its h_i, h_j alone (the same values): the free shape's end moments per unit Y, without the
/// compliance — what measuring a gap needs.
std::array<double, 2> point_load_moments(const element::SectionStiffness& section, double l0, double alpha);

/// The law seen from the nodes' rotations where the beam's ends are connected to its nodes by a
/// hinge (flexibility ∞) or a rotational spring (flexibility 1/k ≥ 0) instead of rigidly:
/// with element end rotations θ_e, M = k_plain θ_e + h Y, c Y = δy_c + hᵀ θ_e and, at each end,
/// M = 0 (hinge) or θ_node = θ_e + f M (spring), the element's own end rotations are condensed
/// out exactly. The result has the same split form in the nodes' rotations,
///     M = K' θ_node + h' Y,   c' Y = δy_c + h'ᵀ θ_node,
/// with K' = (k_plain⁻¹ + F)⁻¹ (the hinged or sprung element's bending block; a hinged end's row
/// zero), h' the fixed-end moments of a unit point load with the connections in place (zero at a
/// hinge) and c' ≥ c the point's compliance with the nodes' rotations held — a simply supported
/// element's a²b²/3EIl0 with both ends hinged (Euler–Bernoulli). Exact, with its α-derivatives.
struct ConnectedLaw {
  PointLoadLaw law;                ///< h', c' and their d/dα
  Eigen::Matrix2d k_plain;         ///< K'
};
ConnectedLaw connected_law(const PointLoadLaw& law, const Eigen::Matrix2d& k_plain, double flexibility_i,
                           double flexibility_j);

/// Default edge δ (README "Contact through element ends").
double default_edge();

}  // namespace tsm::contact
