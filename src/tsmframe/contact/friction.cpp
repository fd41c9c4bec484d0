#include "tsmframe/contact/friction.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "tsmframe/contact/contact_element.hpp"
#include "tsmframe/contact/deflected_normal_element.hpp"

namespace tsm::contact {

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
  const double l0 = data.initial.length, l = r.chord.length, Y = r.forces[3];
  const TangentialCompliance cT = tangential_compliance(data.section.EA, l0, r.alpha, data.edge, f.min_compliance);
  const double slope = w_alpha / l;
  r.friction = return_map(f, Y, slope, f.arc_start + l0 * r.alpha, cT.value);
  if (r.friction.status == FrictionStatus::open) return;
  const double Z = r.friction.Z;
  const double A = l + w_alpha * w_alpha / l;  // F3
  const Vector9 g = alpha_gradient(r.chord, r.alpha, r.normal);
  r.nodal_forces += (Z * A) * g;
  if (!with_tangent) return;

  const Eigen::Vector2d e(r.chord.cos, r.chord.sin);
  const Vector9 grad_l = spread(-e, e, Eigen::Vector2d::Zero());
  const Vector9 grad_A = (1.0 - slope * slope) * grad_l + (2.0 * slope) * grad_w_alpha;  // F11
  add_alpha_hessian(r.symmetric_tangent, Z * A, r.chord, r.alpha, r.normal);
  r.friction_u = g;
  if (r.friction.status != FrictionStatus::slip) {  // stick (or touching here): F12: ∇Z = k_s g, its A k_s g gᵀ symmetric
    const double k_s = (l0 - Z * cT.d_alpha) / cT.value;
    r.symmetric_tangent.noalias() += (A * k_s) * g * g.transpose();
    r.friction_v = Z * grad_A;
    return;
  }
  // F13: ∇Z = (ς μ σ / D)(Z ∇w' − ∇Y), ∇Y = p_c / c + Y_α g, ∇w' = (∇w_α − w' ∇l) / l.
  const PointLoadLaw& law = r.law.connected;
  const double c = law.compliance;
  const double Y_alpha = (law.dh_i * r.deformations[1] + law.dh_j * r.deformations[2] - Y * law.dcompliance) / c;
  const Vector9 point_chord = contact_equilibrium_matrix(r.chord, r.alpha) * Vector4(0.0, law.h_i, law.h_j, 1.0);
  const Vector9 grad_Y = point_chord / c + Y_alpha * g;
  const Vector9 grad_slope = (grad_w_alpha - slope * grad_l) / l;
  const double direction = Z > 0.0 ? 1.0 : -1.0;
  const double D = 1.0 - f.side * direction * f.mu * slope;
  const Vector9 grad_Z = (direction * f.mu * f.side / D) * (Z * grad_slope - grad_Y);
  r.friction_v = A * grad_Z + Z * grad_A;
}

}  // namespace tsm::contact
