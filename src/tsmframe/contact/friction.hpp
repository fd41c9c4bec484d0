#pragma once
// Coulomb friction at node-to-beam contacts in the chord frame (docs/friction.md, F1–F14): the
// tangential law, the return map from the step-start anchor and the consistent tangent, added to
// the frictionless element's response (one point, or each point of a k-point element). Pure and
// local, like the elements themselves.
//
// The node gives the beam Y_N ν + Z τ at α: τ = e + w' n the bent beam's tangent scaled like
// ν = n − w' e (F1). The law's Y stays the force's whole share along n (F2), so friction adds one
// axial point load on the chord, Z a_Z with a_Z = A ∂α/∂x, A = l + w_α²/l (F3). The stick law is
// Z = (s − s_a)/c_T with s = s_e + l0 (α + ρ w_α/l²) the arc length along its member of the
// section whose surface point is under the node (§2; k points: s_e + l0 α) and c_T the
// element's own axial flexibility at α, floored and capped like the normal law (F5, F7);
// Coulomb's |Z| ≤ μ p_N bounds it (F4, F8–F9).

#include <cstdint>

#include <Eigen/Core>

namespace tsm::contact {

struct ContactElementData;
struct ContactResponse;
struct MultiPointElementData;
struct MultiPointResponse;
using Vector9 = Eigen::Matrix<double, 9, 1>;

/// Where the return map left a point.
enum class FrictionStatus : std::uint8_t {
  none,        ///< μ = 0: frictionless, nothing formed
  open,        ///< the law would pull (p₀ ≤ 0): Z = 0
  stick,
  slip,
};

/// What a point's friction needs beside the element: its μ, the side it presses from, and its
/// anchor on the member (fixed within a step).
struct FrictionData {
  double mu = 0.0;
  int side = 0;               ///< σ: +1 along n, −1 against (the compression is −σ Y_N)
  bool anchored = false;
  double anchor = 0.0;        ///< s_a,n: the step-start anchor's arc length along the member
  double arc_start = 0.0;     ///< s_e: the member's length as drawn before this element (F5)
  double min_compliance = 0.0;  ///< the stiffness cap along the chord (ContactGeometry::cap_compliance)
};

/// The return map's result at one evaluation.
struct FrictionResult {
  FrictionStatus status = FrictionStatus::none;
  double Z = 0.0;           ///< the friction force's share along e (F2)
  double tangential = 0.0;  ///< its magnitude along the bent tangent, signed: Z q (q = |τ|)
  double normal_Y = 0.0;    ///< Y_N = Y − Z w': the normal force's share along n
  double slope = 0.0;       ///< w' = w_α / l
  double arc = 0.0;         ///< s: the point's arc length along its member
  double trial_anchor = 0.0;  ///< s_a,trial: the anchor this iterate would leave (F9)
};

/// c_T at α (F7) and its α-rate where the axial flexibility binds.
struct TangentialCompliance {
  double value = 0.0, d_alpha = 0.0;
};
TangentialCompliance tangential_compliance(double EA, double l0, double alpha, double edge, double min_compliance);

/// The return map alone (F8–F9): from the law's Y, the point's slope w', arc length s and c_T.
FrictionResult return_map(const FrictionData& friction, double Y, double slope, double arc, double compliance);

/// Adds the point's friction to `r` (formed by chord_frame_parts, and turned to the bent normal
/// where asked for: `w_alpha` its slope w_α, `grad_w_alpha` ∇w_α, both zero along the chord's
/// normal): nodal forces, Z A ∂²α and the stick part into symmetric_tangent, the rest as the
/// rank-one pair friction_u friction_vᵀ (F11–F14), and r.friction. μ = 0: nothing (F §8).
void add_friction(const ContactElementData& data, double w_alpha, const Vector9& grad_w_alpha, bool with_tangent,
                  ContactResponse& r);
/// The same for the points of a k-point element in the chord frame, each along its chord's
/// normal (a frictional element's points all are; ContactSet::active_contacts): ∇Y_p couples the
/// points through C⁻¹ and the law's α-rates `dpoint_forces` (∂Y_p/∂α_q). Into r.friction (per
/// point), nodal_forces, symmetric_tangent and tangent, and the pairs friction_u friction_vᵀ.
void add_multi_point_friction(const MultiPointElementData& data, const Eigen::MatrixXd& dpoint_forces,
                              bool with_tangent, MultiPointResponse& r);

}  // namespace tsm::contact
