#include "tsmframe/contact/multi_point_deflected_normal.hpp"

#include <algorithm>
#include <array>
#include <utility>

#include <Eigen/LU>
#include <Eigen/SparseCore>

#include "tsmframe/contact/deflected_normal_element.hpp"
#include "tsmframe/contact/multi_point_law.hpp"

namespace tsm::contact {
namespace {

using Eigen::MatrixXd;
using Eigen::Vector2d;
using Eigen::VectorXd;

/// The dofs of nodes i, j and contact node p among the element's 3(2 + k).
std::array<int, 9> point_dofs(int point) {
  return {0, 1, 2, 3, 4, 5, 6 + 3 * point, 7 + 3 * point, 8 + 3 * point};
}

/// The law as multi_point_response evaluates it (connected where the ends are hinged or sprung,
/// floored), its forces' α-rates, and the beam's own H and ∂H/∂α (what θ_e needs, N9).
struct ElementLaw {
  Eigen::Matrix2Xd h_raw, dh_raw;
  MultiPointLaw connected;
  Eigen::Matrix2d k_plain;
  MultiPointForces forces;
};
ElementLaw element_law(const MultiPointElementData& data, const MultiPointResponse& r) {
  const int k = data.size();
  MultiPointLaw law = multi_point_law(data.section, data.initial.length, r.alpha, data.edge, data.min_compliance);
  ElementLaw out{law.h, law.dh, {}, data.k0.bottomRightCorner<2, 2>(), {}};
  if (data.connected()) {
    ConnectedMultiPointLaw c = connected_multi_point_law(law, out.k_plain, data.flexibility_i, data.flexibility_j);
    law = std::move(c.law);
    out.k_plain = c.k_plain;
  }
  out.connected = std::move(law);
  out.forces = multi_point_forces(out.connected, out.k_plain, r.deformations.segment<2>(1), r.deformations.tail(k));
  return out;
}

/// The element's own end rotations θ_e and their rates in d = (δl, θ, δy) and α (N9, N19): the
/// nodes' θ where the ends are rigid; else θ_e = k⁻¹ (M − H Y), the beam's own k and H.
struct OwnEndRotations {
  Vector2d theta;
  Eigen::Matrix2Xd d, d_alpha;
};
OwnEndRotations own_rotations(const MultiPointElementData& data, const ElementLaw& law, const MultiPointResponse& r,
                           const MatrixXd& dY) {
  const int k = data.size();
  OwnEndRotations own{r.deformations.segment<2>(1), Eigen::Matrix2Xd::Zero(2, 3 + k), Eigen::Matrix2Xd::Zero(2, k)};
  if (!data.connected()) {
    own.d.middleCols<2>(1).setIdentity();
    return own;
  }
  const Eigen::Matrix2d k_inverse = data.k0.bottomRightCorner<2, 2>().inverse();
  const VectorXd Y = r.forces.tail(k);
  Eigen::Matrix2Xd dM = law.connected.h * dY;  // ∂M/∂d = [0, K', 0] + H' ∂Y/∂d
  dM.middleCols<2>(1) += law.k_plain;
  own.theta = k_inverse * (r.forces.segment<2>(1) - law.h_raw * Y);  // N9
  own.d = k_inverse * (dM - law.h_raw * dY);
  own.d_alpha = k_inverse * (law.forces.dmoments - law.h_raw * law.forces.dpoint_forces - law.dh_raw * Y.asDiagonal());
  return own;
}

/// The slopes w_α at the points (N16) and, when asked for, their rates (N19): ∂w/∂d (k × (3+k))
/// and ∂w/∂α ((p, q) = ∂w_α,p/∂α_q).
struct Slopes {
  VectorXd value;
  MatrixXd d, d_alpha;
};
Slopes shape_slopes(const MultiPointElementData& data, const MultiPointResponse& r, const ElementLaw& law, bool with_rates) {
  const int k = data.size();
  const double l0 = data.initial.length;
  const VectorXd Y = r.forces.tail(k);
  // ∂Y/∂d = C⁻¹ Pᵀ, P = [0; H'; I] (K14).
  MatrixXd dY = MatrixXd::Zero(k, 3 + k);
  dY.middleCols(1, 2) = r.point_stiffness * law.connected.h.transpose();
  dY.rightCols(k) = r.point_stiffness;
  const OwnEndRotations own = own_rotations(data, law, r, dY);
  // w = −Dhᵀ θ_e + S Y: Dh the free shape's slopes, S_pp = ½ c_α(α_p), S_pq = l0 ∂C/∂x(a_p, a_q).
  Eigen::Matrix2Xd Dh(2, k), DDh(2, k);
  MatrixXd S(k, k), own_rate = MatrixXd::Zero(k, k);  // own_rate: ∂S/∂α with Y held, times Y
  for (int p = 0; p < k; ++p) {
    const ShapeSlopeTerms t = shape_slope_terms(data.section, l0, r.alpha[p]);  // N2, N12 (held beyond the ends)
    Dh.col(p) = t.dh;
    DDh.col(p) = t.ddh;
    S(p, p) = 0.5 * t.dc;
    own_rate(p, p) = 0.5 * t.ddc * Y[p];
    const double x = std::clamp(r.alpha[p], 0.0, 1.0) * l0;
    const bool p_inside = r.alpha[p] >= 0.0 && r.alpha[p] <= 1.0;
    for (int q = 0; q < k; ++q) {
      if (q == p) continue;
      const double xi = std::clamp(r.alpha[q], 0.0, 1.0) * l0;
      S(p, q) = l0 * clamped_influence_slope(data.section, l0, x, xi);  // N16
      if (!with_rates) continue;
      if (p_inside) own_rate(p, p) += l0 * l0 * clamped_influence_curvature(data.section, l0, x, xi) * Y[q];  // N17
      if (r.alpha[q] >= 0.0 && r.alpha[q] <= 1.0)
        own_rate(p, q) = l0 * l0 * clamped_influence_cross_slope(data.section, l0, x, xi) * Y[q];
    }
  }
  Slopes w;
  w.value = -Dh.transpose() * own.theta + S * Y;  // N16
  if (with_rates) {
    w.d = -Dh.transpose() * own.d + S * dY;  // N19
    w.d_alpha = -Dh.transpose() * own.d_alpha + S * law.forces.dpoint_forces + own_rate;
    w.d_alpha.diagonal() -= DDh.transpose() * own.theta;
  }
  for (int p = 0; p < k; ++p) {  // a chord point: w_α,p ≡ 0, its force along n whatever the shape
    if (data.points[p].normal == ContactNormal::deflected) continue;
    w.value[p] = 0.0;
    if (!with_rates) continue;
    w.d.row(p).setZero();
    w.d_alpha.row(p).setZero();
  }
  return w;
}

}  // namespace

Eigen::VectorXd multi_point_shape_slopes(const MultiPointElementData& data, const MultiPointResponse& response) {
  return shape_slopes(data, response, element_law(data, response), false).value;
}

MultiPointResponse multi_point_deflected_response(const MultiPointElementData& data, const Eigen::VectorXd& d,
                                                  double previous_rotation, bool with_tangent) {
  // α, δy and S as the chord's-normal element measures them (N5); its J S, tangent and point loads.
  MultiPointResponse r = multi_point_response(data, d, previous_rotation, with_tangent);
  const int k = data.size(), size = 3 * (2 + k);
  if (k == 0) return r;
  const ElementLaw law = element_law(data, r);
  const Slopes w = shape_slopes(data, r, law, with_tangent);
  const VectorXd Y = r.forces.tail(k);
  const double l = r.chord.length;
  // G and B have nine entries per column (i, j, c_p), J as many: their products are taken
  // sparse (multi_point_response), O(k²) work for k points where dense ones were O(k³).
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(9 * k);
  for (int p = 0; p < k; ++p) {
    const Vector9 g = alpha_gradient(r.chord, r.alpha[p], r.normal[p]);
    const std::array<int, 9> dofs = point_dofs(p);
    for (int a = 0; a < 9; ++a) entries.emplace_back(dofs[a], p, g[a]);
  }
  Eigen::SparseMatrix<double> G(size, k);  // column p: ∂α_p/∂x (N10 on i, j, c_p)
  G.setFromTriplets(entries.begin(), entries.end());
  const Eigen::SparseMatrix<double> B = G * w.value.asDiagonal();  // column p: w_α,p ∂α_p/∂x
  r.nodal_forces -= B * Y;                      // N18: J S − Σ_p T_p ∂α_p/∂x
  // p_c,p lives on i, j and c_p too (J's columns N, M and Y_p): kept sparse for the products below.
  const Eigen::SparseMatrix<double> point_chord = r.point_u.sparseView();
  r.point_u -= B;  // N18: p_ν,p = p_c,p − w_α,p ∂α_p/∂x
  r.force_per_Y = (1.0 + (w.value / l).array().square()).sqrt().matrix();  // |ν_p|, N3
  if (!with_tangent) return r;

  // N20: K = K_chord − Σ_p ∂α_p/∂x (∇T_p)ᵀ − Σ_p T_p ∂²α_p, ∇T_p = w_α,p ∇Y_p + Y_p ∇w_α,p; N21 splits it.
  const Eigen::SparseMatrix<double> J = multi_point_equilibrium_matrix(r.chord, r.alpha).sparseView();
  const MatrixXd dw = J * w.d.transpose() + G * w.d_alpha.transpose();  // column p: ∇w_α,p (N19)
  const MatrixXd& C_inverse = r.point_stiffness;
  const MatrixXd Y_dw = Y.asDiagonal() * dw.transpose();
  const MatrixXd turning = G * Y_dw;  // Σ_p Y_p ∂α_p/∂x ∇w_α,pᵀ
  const MatrixXd B_C_inverse = B * C_inverse;
  const MatrixXd lever = B_C_inverse * point_chord.transpose();
  r.symmetric_tangent += -(lever + lever.transpose()) - (turning + turning.transpose());
  r.symmetric_tangent += B_C_inverse * B.transpose();
  for (int p = 0; p < k; ++p) {  // −T_p ∂²α_p on i, j, c_p
    const Matrix9 hessian = alpha_hessian(r.chord, r.alpha[p], r.normal[p]);
    const std::array<int, 9> dofs = point_dofs(p);
    const double T = Y[p] * w.value[p];
    for (int a = 0; a < 9; ++a)
      for (int b = 0; b < 9; ++b) r.symmetric_tangent(dofs[a], dofs[b]) -= T * hessian(a, b);
  }
  if (data.sliding_term) {  // N21: column p gains w_α,p P_ν C⁻¹ e_p − Σ_q w_α,q (∂Y_q/∂α_p) g_q + Y_p ∇w_α,p
    const Eigen::SparseMatrix<double> point_normal = point_chord - B;  // p_ν, as r.point_u
    r.sliding_u += point_normal * (C_inverse * w.value.asDiagonal()) - B * law.forces.dpoint_forces + dw * Y.asDiagonal();
    r.sliding_v = MatrixXd(G);
  }
  r.tangent = r.symmetric_tangent;
  if (data.sliding_term) r.tangent += r.sliding_u * G.transpose();
  return r;
}

}  // namespace tsm::contact
