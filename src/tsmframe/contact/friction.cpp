#include "tsmframe/contact/friction.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "tsmframe/contact/contact_element.hpp"
#include "tsmframe/contact/deflected_normal_element.hpp"
#include "tsmframe/contact/multi_point_element.hpp"

namespace tsm::contact {
namespace {

/// One point's friction on the translations of i, j and its node (the 9-vector's places): the
/// return map's result and what the force f += Z A g and its tangent are made of (F3, F11–F13).
struct PointFriction {
  FrictionResult result;
  double A = 0.0;            ///< l + w_α²/l
  Vector9 g, grad_A;         ///< ∂α/∂x, ∇A
  double stick_stiffness = 0.0;  ///< k_s (stick): ∇Z = k_s g
  /// slip: ∇Z = slip_rate · (Z ∇w' − ∇Y); the Z ∇w' part here (∇Y is the caller's, over its dofs)
  double slip_rate = 0.0;
  Vector9 slope_part = Vector9::Zero();
  /// stick: ∇Z's part beyond k_s g — the gap's term of the arc length (F5 with §2's offset·w'),
  /// (l0/c_T) ∇(ρ w_α / l²)
  Vector9 arc_part = Vector9::Zero();
  bool acts() const { return result.status == FrictionStatus::stick || result.status == FrictionStatus::slip; }
};

PointFriction point_friction(const FrictionData& f, const element::InitialChord& initial, double EA, double edge,
                             const element::Chord& chord, double alpha, double rho, double Y, double w_alpha,
                             const Vector9& grad_w_alpha, const ShapeSlopeAt& arc_slope) {
  PointFriction p;
  const double l0 = initial.length, l = chord.length;
  const TangentialCompliance cT = tangential_compliance(EA, l0, alpha, edge, f.min_compliance);
  const double slope = w_alpha / l;
  // The arc length of the section whose surface point is under the node: the foot of the bent
  // shape's normal, α + ρ w_α / l² (§2) — a beam turning about the contact point does not slip.
  const double ws = arc_slope.w_alpha;  // zero where not formed: an element of several points
  p.result = return_map(f, Y, slope, f.arc_start + l0 * (alpha + rho * ws / (l * l)), cT.value);
  if (!p.acts()) return p;
  p.A = l + w_alpha * w_alpha / l;  // F3
  p.g = alpha_gradient(chord, alpha, rho);
  const Eigen::Vector2d e(chord.cos, chord.sin);
  const Vector9 grad_l = spread(-e, e, Eigen::Vector2d::Zero());
  p.grad_A = (1.0 - slope * slope) * grad_l + (2.0 * slope) * grad_w_alpha;  // F11
  const double Z = p.result.Z;
  if (p.result.status == FrictionStatus::stick) {
    p.stick_stiffness = (l0 - Z * cT.d_alpha) / cT.value;  // F12
    if (ws != 0.0 || rho != 0.0) {
      const Vector9 grad_rho = contact_equilibrium_matrix(chord, alpha).col(3);  // ∇(r·n): J's Y column
      p.arc_part = (l0 / cT.value / (l * l)) *
                   (ws * grad_rho + rho * arc_slope.gradient - (2.0 * rho * ws / l) * grad_l);
    }
    return p;
  }
  const double direction = Z > 0.0 ? 1.0 : -1.0;
  p.slip_rate = direction * f.mu * f.side / (1.0 - f.side * direction * f.mu * slope);  // F13
  p.slope_part = (Z / l) * (grad_w_alpha - slope * grad_l);
  return p;
}

}  // namespace

TangentialCompliance tangential_compliance(double EA, double l0, double alpha, double edge, double min_compliance) {
  const double axial = alpha * (1.0 - alpha) * l0 / EA;  // c_ax: a bar held at both ends, loaded at α (F6)
  const double floor = std::max(edge * (1.0 - edge) * l0 / EA, min_compliance);
  if (axial > floor) return {axial, (1.0 - 2.0 * alpha) * l0 / EA};  // F7
  return {floor, 0.0};
}

FrictionResult return_map(const FrictionData& f, double Y, double slope, double arc, double compliance) {
  FrictionResult out;
  out.slope = slope;
  out.arc = arc;
  out.normal_Y = Y;
  out.trial_anchor = arc;
  const double pressure = -f.side * Y;  // p₀: the law's compression
  if (pressure <= 0.0) {
    out.status = FrictionStatus::open;
    return out;
  }
  // Touched at this iterate: anchored where it is, so Z = 0 with the stick's stiffness (without
  // it Newton's next iterate would move the point freely, and off the narrow stick zone).
  const double anchor = f.anchored ? f.anchor : arc;
  const double gap = arc - anchor;  // g_T (F7)
  const double trial = gap / compliance;
  const double direction = gap >= 0.0 ? 1.0 : -1.0;                   // ς
  const double D = 1.0 - f.side * direction * f.mu * slope;            // F8
  // F9, step 4. A step starts with a slipping point's anchor where its force is on the cone's
  // edge: it sticks there, g_T's rounding (arc lengths' last bits, against a stick zone
  // μ p c_T wide) allowed for — a slip tangent would let the predictor move the point freely.
  const double rounding = 8.0 * std::numeric_limits<double>::epsilon() * std::max(std::abs(arc), std::abs(anchor));
  if (std::abs(gap) <= f.mu * pressure / D * compliance + rounding) {
    out.status = FrictionStatus::stick;
    out.Z = trial;
    out.trial_anchor = anchor;
  } else {                                                             // F9, step 5
    out.status = FrictionStatus::slip;
    out.Z = direction * f.mu * pressure / D;
    out.trial_anchor = arc - compliance * out.Z;
  }
  out.normal_Y = Y - out.Z * slope;                                   // F2
  out.tangential = out.Z * std::sqrt(1.0 + slope * slope);
  return out;
}

void add_friction(const ContactElementData& data, double w_alpha, const Vector9& grad_w_alpha, bool with_tangent,
                  ContactResponse& r) {
  const FrictionData& f = data.friction;
  if (f.mu == 0.0) return;
  const double Y = r.forces[3];
  // Along the chord's normal the force leaves the shape's slope out; the arc length reads it.
  const ShapeSlopeAt arc = data.normal == ContactNormal::chord ? shape_slope_at(data, r, with_tangent)
                                                                 : ShapeSlopeAt{w_alpha, grad_w_alpha};
  const PointFriction p = point_friction(f, data.initial, data.section.EA, data.edge, r.chord, r.alpha, r.normal, Y,
                                         w_alpha, grad_w_alpha, arc);
  r.friction = p.result;
  if (!p.acts()) return;
  const double Z = p.result.Z;
  r.nodal_forces += (Z * p.A) * p.g;
  if (!with_tangent) return;
  add_alpha_hessian(r.symmetric_tangent, Z * p.A, r.chord, r.alpha, r.normal);
  r.friction_u = p.g;
  if (p.result.status == FrictionStatus::stick) {  // ∇Z = k_s g: A k_s g gᵀ symmetric
    r.symmetric_tangent.noalias() += (p.A * p.stick_stiffness) * p.g * p.g.transpose();
    r.friction_v = Z * p.grad_A + p.A * p.arc_part;
    return;
  }
  // ∇Y = p_c / c + Y_α g: the chord's point load p_c (the response's point_u, turned back from the
  // bent normal's J_ν (0, h, 1)ᵀ = p_c − w_α g), the law's α-rate.
  const PointLoadLaw& law = r.law.connected;
  const double c = law.compliance;
  const double Y_alpha = (law.dh_i * r.deformations[1] + law.dh_j * r.deformations[2] - Y * law.dcompliance) / c;
  const Vector9 grad_Y = (r.point_u + w_alpha * p.g) / c + Y_alpha * p.g;
  r.friction_v = p.A * p.slip_rate * (p.slope_part - grad_Y) + Z * p.grad_A;
}

void add_multi_point_friction(const MultiPointElementData& data, const Eigen::MatrixXd& dpoint_forces,
                              bool with_tangent, MultiPointResponse& r) {
  const int k = data.size(), size = 3 * (2 + k);
  r.friction.assign(static_cast<size_t>(k), FrictionResult{});
  r.friction_u = Eigen::MatrixXd::Zero(size, k);
  r.friction_v = Eigen::MatrixXd::Zero(size, k);
  const auto places = [](int point) { return std::array<int, 9>{0, 1, 2, 3, 4, 5, 6 + 3 * point, 7 + 3 * point, 8 + 3 * point}; };
  const auto widen = [&](const Vector9& local, int point) {  // the 9 places of i, j, c_p in the element's dofs
    Eigen::VectorXd v = Eigen::VectorXd::Zero(size);
    const std::array<int, 9> at = places(point);
    for (int a = 0; a < 9; ++a) v[at[a]] += local[a];
    return v;
  };
  std::vector<Eigen::VectorXd> g(static_cast<size_t>(k));  // every point's ∂α/∂x: ∇Y_p reads them all
  for (int q = 0; q < k; ++q) g[q] = widen(alpha_gradient(r.chord, r.alpha[q], r.normal[q]), q);
  for (int p = 0; p < k; ++p) {
    const FrictionData& f = data.points[p].friction;
    if (f.mu == 0.0) continue;
    // Every point of a frictional element pushes along its chord's normal (w' = 0; active_contacts).
    // The arc length reads no shape slope here (the k-point shape's is not differentiated yet).
    const PointFriction pf = point_friction(f, data.initial, data.section.EA, data.edge, r.chord, r.alpha[p],
                                            r.normal[p], r.forces[3 + p], 0.0, Vector9::Zero(), ShapeSlopeAt{});
    r.friction[p] = pf.result;
    if (!pf.acts()) continue;
    const double Z = pf.result.Z;
    r.nodal_forces += (Z * pf.A) * g[p];
    if (!with_tangent) continue;
    Matrix9 hessian = Matrix9::Zero();
    add_alpha_hessian(hessian, Z * pf.A, r.chord, r.alpha[p], r.normal[p]);
    if (pf.result.status == FrictionStatus::stick) hessian.noalias() += (pf.A * pf.stick_stiffness) * pf.g * pf.g.transpose();
    const std::array<int, 9> at = places(p);
    for (int a = 0; a < 9; ++a)
      for (int b = 0; b < 9; ++b) {
        r.symmetric_tangent(at[a], at[b]) += hessian(a, b);
        r.tangent(at[a], at[b]) += hessian(a, b);
      }
    r.friction_u.col(p) = g[p];
    Eigen::VectorXd v = Z * widen(pf.grad_A, p) + pf.A * widen(pf.arc_part, p);
    if (pf.result.status == FrictionStatus::slip) {
      // ∇Y_p = Σ_q C⁻¹(p, q) P_q + Σ_q ∂Y_p/∂α_q g_q (K14, K13).
      Eigen::VectorXd grad_Y = r.point_u * r.point_stiffness.row(p).transpose();
      for (int q = 0; q < k; ++q) grad_Y += dpoint_forces(p, q) * g[q];
      v += pf.A * pf.slip_rate * (widen(pf.slope_part, p) - grad_Y);
    }
    r.friction_v.col(p) = v;
    r.tangent.noalias() += r.friction_u.col(p) * v.transpose();
  }
}

}  // namespace tsm::contact
