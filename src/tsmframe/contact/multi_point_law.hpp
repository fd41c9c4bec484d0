#pragma once
// The contact element's force law with k interior points (docs/contact-k-points.md; issue 27):
// a beam in its chord frame with end rotations θ = (θ_i, θ_j) and k transverse point forces Y_p
// at α_p, split as "the plain element plus k point loads",
//     C Y = δy + Hᵀ θ,     M = k_plain θ + H Y                                          (K2)
// with H = [h(α_1) … h(α_k)] the fixed-end moments per unit point force (contact_force_law's h)
// and C the points' clamped–clamped flexibility (K5), C_pp = contact_force_law's c(α_p). k = 0 is
// the plain element, k = 1 is point_load_law exactly. Pure and local, like contact_force_law.

#include <vector>

#include <Eigen/Core>

#include "tsmframe/element/force_law.hpp"

namespace tsm::contact {

/// C(x, ξ) of K5: the deflection at x from a unit transverse force at ξ on a beam of length l0
/// with both ends held in translation and rotation (positions as lengths from node i, clamped to
/// [0, l0]). Symmetric in x, ξ; C(a, a) is point_load_law's compliance at α = a/l0 (no floor).
double clamped_influence(const element::SectionStiffness& section, double l0, double x, double xi);
/// ∂C(x, ξ)/∂x at l0 and ξ held (K9); 0 where x lies outside [0, l0].
double clamped_influence_slope(const element::SectionStiffness& section, double l0, double x, double xi);
/// Its second derivatives at l0 held (docs/contact-normal.md N17): ∂²C/∂x² (0 where x lies outside
/// [0, l0]; ξ clamped as above) and ∂²C/∂x∂ξ (0 where x or ξ lies outside). Both are continuous
/// where the points meet (the two sides differ by a(x − ξ) + b(x − ξ)³), so there either side's.
double clamped_influence_curvature(const element::SectionStiffness& section, double l0, double x, double xi);
double clamped_influence_cross_slope(const element::SectionStiffness& section, double l0, double x, double xi);

/// The floor of a point's compliance, max((δ(1−δ) l0)³ / 3EI, min_compliance), δ = edge: what
/// point_load_law clamps c to next to a node (K10), and the pair floor's bound (K11).
double compliance_floor(const element::SectionStiffness& section, double l0, double edge, double min_compliance);

/// The α-derivatives of C, ∂C/∂α_p for p = 0 … k−1, in O(k²) numbers rather than k dense
/// matrices: moving point p changes row and column p of C (K9; the hinge and spring terms of
/// K12 too), and a pair floor binding p with q also C_qq (K11).
struct ComplianceRates {
  /// Row p: ∂C_pq/∂α_p for every q (the diagonal ∂C_pp/∂α_p); ∂C/∂α_p is that row and its
  /// mirror column.
  Eigen::MatrixXd rows;
  struct Diagonal {
    int p = 0, q = 0;      ///< ∂C_qq/∂α_p (q ≠ p), from a pair floor
    double value = 0.0;
  };
  std::vector<Diagonal> diagonals;
  /// ∂C/∂α_p · Y.
  Eigen::VectorXd times(int p, const Eigen::VectorXd& Y) const;
  /// ∂C/∂α_p as a dense k×k matrix (for checks; O(k²) each).
  Eigen::MatrixXd dense(int p) const;
};

/// The law at k points: H, C and their α-derivatives.
struct MultiPointLaw {
  Eigen::Matrix2Xd h;           ///< H (2×k): column p = (h_i, h_j) at α_p (K4)
  Eigen::MatrixXd compliance;   ///< C (k×k) with its floors (K10, K11): symmetric positive definite
  Eigen::Matrix2Xd dh;          ///< column p = ∂h_p/∂α_p; ∂H/∂α_p is that column alone (K8)
  ComplianceRates dcompliance;  ///< ∂C/∂α_p, p = 0 … k−1 (K9–K11)
  int size() const { return static_cast<int>(h.cols()); }
};

/// The law at positions α (any number k ≥ 0; h and C use α clamped to [0, 1], derivatives 0
/// outside). Diagonal entries, h and their derivatives are point_load_law's own, floor included
/// (K10); the off-diagonal ones are K5; then the pair floor (K11) keeps C positive definite where
/// two points come within about edge·l0 of each other.
MultiPointLaw multi_point_law(const element::SectionStiffness& section, double l0, const Eigen::VectorXd& alpha,
                              double edge, double min_compliance = 0.0);

/// The law seen from the nodes' rotations where the element's ends are joined to its nodes by a
/// hinge (flexibility ∞) or a rotational spring (1/k), condensed exactly as connected_law does
/// for k = 1 (K12a, K12b): M = K' θ_node + H' Y, C' Y = δy + H'ᵀ θ_node.
struct ConnectedMultiPointLaw {
  MultiPointLaw law;        ///< H', C' and their α-derivatives
  Eigen::Matrix2d k_plain;  ///< K', the hinged or sprung element's bending block
};
ConnectedMultiPointLaw connected_multi_point_law(const MultiPointLaw& law, const Eigen::Matrix2d& k_plain,
                                                 double flexibility_i, double flexibility_j);

/// How the point forces enter S = (N, M, Y) (or (N, Q, M, Y) in the cantilever frame) and what
/// they stiffen (K14): P = [0_{1×k}; H; I_k] and the points' stiffness C⁻¹ (symmetric).
struct PointForceMap {
  Eigen::MatrixXd P;          ///< (3+k)×k
  Eigen::MatrixXd stiffness;  ///< C⁻¹ (k×k)
};
PointForceMap point_force_map(const MultiPointLaw& law);
/// ∂S/∂d = diag(axial, k_plain, 0_k) + P C⁻¹ Pᵀ (K14).
Eigen::MatrixXd law_tangent(const PointForceMap& map, double axial, const Eigen::Matrix2d& k_plain);

/// The forces of the law (K2) at given deformations, and their α-derivatives (K13).
struct MultiPointForces {
  Eigen::Vector2d moments = Eigen::Vector2d::Zero();  ///< M = (M_i, M_j)
  Eigen::VectorXd point_forces;                       ///< Y (k)
  Eigen::Matrix2Xd dmoments;                          ///< column p = ∂M/∂α_p
  Eigen::MatrixXd dpoint_forces;                      ///< column p = ∂Y/∂α_p (k×k)
};
MultiPointForces multi_point_forces(const MultiPointLaw& law, const Eigen::Matrix2d& k_plain,
                                    const Eigen::Vector2d& theta, const Eigen::VectorXd& deflections);

}  // namespace tsm::contact
