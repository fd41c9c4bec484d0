#include "tsmframe/contact/deflected_normal_element.hpp"

#include <algorithm>

#include <Eigen/LU>

#include "tsmframe/element/deflected_shape.hpp"

namespace tsm::contact {
namespace {

using Eigen::Vector2d;
using Row4 = Eigen::Matrix<double, 1, 4>;
using Matrix24 = Eigen::Matrix<double, 2, 4>;

/// S's dependence on d = (δl, θ_i, θ_j, δy_c) and on α, for M and Y (K13 with k = 1).
struct LawRates {
  Row4 dY = Row4::Zero();        ///< ∂Y/∂d = (0, h, 1)/c
  Matrix24 dM = Matrix24::Zero();  ///< ∂M/∂d
  double dY_dalpha = 0.0;
  Vector2d dM_dalpha = Vector2d::Zero();
};
LawRates law_rates(const ChordFrameLaw& law, const Vector2d& theta, double Y) {
  const PointLoadLaw& p = law.connected;
  const Vector2d h(p.h_i, p.h_j), dh(p.dh_i, p.dh_j);
  LawRates rates;
  rates.dY << 0.0, h.transpose() / p.compliance, 1.0 / p.compliance;
  rates.dM.middleCols<2>(1) = law.k_plain + h * h.transpose() / p.compliance;
  rates.dM.col(3) = h / p.compliance;
  rates.dY_dalpha = (dh.dot(theta) - Y * p.dcompliance) / p.compliance;
  rates.dM_dalpha = dh * Y + h * rates.dY_dalpha;
  return rates;
}

/// The element's own end rotations θ_e and their rates (N9): the nodes' θ where the ends are
/// rigid; where hinged or sprung, from M = k θ_e + h Y with the beam's own k and h.
struct OwnRotations {
  Vector2d theta;
  Matrix24 d = Matrix24::Zero();
  Vector2d d_alpha = Vector2d::Zero();
};
OwnRotations own_rotations(const ContactElementData& data, const ChordFrameLaw& law, const LawRates& rates,
                           const Vector2d& theta, const Vector2d& moments, double Y) {
  OwnRotations own{theta};
  if (!data.connected()) {
    own.d.middleCols<2>(1).setIdentity();
    return own;
  }
  const Eigen::Matrix2d k_inverse = data.k0.bottomRightCorner<2, 2>().inverse();
  const Vector2d h(law.raw.h_i, law.raw.h_j), dh(law.raw.dh_i, law.raw.dh_j);
  own.theta = k_inverse * (moments - h * Y);
  own.d = k_inverse * (rates.dM - h * rates.dY);
  own.d_alpha = k_inverse * (rates.dM_dalpha - h * rates.dY_dalpha - dh * Y);
  return own;
}

/// w_α = dw/dα at the contact point and its rates in d and α (N2, N13).
struct Slope {
  double value = 0.0;
  Row4 d = Row4::Zero();
  double d_alpha = 0.0;
};
Slope shape_slope(const ContactElementData& data, const ContactResponse& r, const ChordFrameLaw& law, const LawRates& rates) {
  const Vector2d theta = r.deformations.segment<2>(1), moments = r.forces.segment<2>(1);
  const double Y = r.forces[3];
  const OwnRotations own = own_rotations(data, law, rates, theta, moments, Y);
  const ShapeSlopeTerms t = shape_slope_terms(data.section, data.initial.length, r.alpha);
  Slope w;
  w.value = -t.dh.dot(own.theta) + 0.5 * t.dc * Y;                                       // N2
  w.d = -t.dh.transpose() * own.d + 0.5 * t.dc * rates.dY;                                // N13
  w.d_alpha = -t.ddh.dot(own.theta) + 0.5 * t.ddc * Y - t.dh.dot(own.d_alpha) + 0.5 * t.dc * rates.dY_dalpha;
  return w;
}

}  // namespace

Vector9 alpha_gradient(const element::Chord& chord, double alpha, double rho) {
  const Vector2d e(chord.cos, chord.sin), n(-chord.sin, chord.cos);
  const double l = chord.length;
  return spread(((alpha - 1.0) / l) * e - (rho / (l * l)) * n, (rho / (l * l)) * n - (alpha / l) * e, e / l);
}

Matrix9 alpha_hessian(const element::Chord& chord, double alpha, double rho) {
  Matrix9 H = Matrix9::Zero();
  add_alpha_hessian(H, 1.0, chord, alpha, rho);
  return H;
}

void add_alpha_hessian(Matrix9& K, double scale, const element::Chord& chord, double alpha, double rho) {
  const Vector2d e(chord.cos, chord.sin), n(-chord.sin, chord.cos), zero = Vector2d::Zero();
  const double l = chord.length, s = scale / (l * l);
  const Vector9 a1 = spread(-n, n, zero), a2 = spread(-e, zero, e);  // n·dΔ, e·dr
  const Vector9 a3 = spread(-e, e, zero), b2 = spread(-n, zero, n);  // e·dΔ, n·dr
  // l² ∂²α = −sym(a2, a3) + sym(b2, a1) − (2ρ/l) sym(a1, a3) + 2α (a3 a3ᵀ − a1 a1ᵀ)     (N11)
  //        = sym(a3, α a3 − a2 − (2ρ/l) a1) + sym(a1, b2 − α a1),  sym(x, y) = x yᵀ + y xᵀ.
  add_symmetric(K, s * a3, alpha * a3 - a2 - (2.0 * rho / l) * a1);
  add_symmetric(K, s * a1, b2 - alpha * a1);
}

ShapeSlopeTerms shape_slope_terms(const element::SectionStiffness& section, double l0, double alpha) {
  const double s = std::clamp(alpha, 0.0, 1.0), psi = section.shear_flexibility, span = l0 * l0 + 12.0 * psi;
  const double p = s * (1.0 - s) * l0 * l0, dp = (1.0 - 2.0 * s) * l0 * l0;
  const double omega = p * p + 3.0 * psi * (l0 * l0 + p) + 36.0 * psi * psi;  // Eq. 9
  const double scale = 3.0 * section.EI * l0 * span;
  const element::RotationShape dN = element::rotation_shape_slope(section, l0, s);
  ShapeSlopeTerms t;
  t.dh = Vector2d(-dN.i, -dN.j);
  t.dc = dp * (omega + p * (2.0 * p + 3.0 * psi)) / scale;  // point_load_law's dc/dα, no floor
  if (alpha < 0.0 || alpha > 1.0) return t;  // beyond the ends the direction is held (hand-over)
  // N12: d²N/ds² is linear in s; d²c/dα² from c = f(p)/scale, f(p) = p Ω(p).
  t.ddh = -2.0 * l0 / span * Vector2d(3.0 * l0 * l0 * s - 2.0 * l0 * l0 - 6.0 * psi, 3.0 * l0 * l0 * s - l0 * l0 + 6.0 * psi);
  t.ddc = (-2.0 * l0 * l0 * (omega + 2.0 * p * p + 3.0 * psi * p) + dp * dp * (6.0 * p + 6.0 * psi)) / scale;
  return t;
}

ShapeSlopeAt shape_slope_at(const ContactElementData& data, const ContactResponse& r, bool with_gradient) {
  const LawRates rates = law_rates(r.law, r.deformations.segment<2>(1), r.forces[3]);
  const Slope w = shape_slope(data, r, r.law, rates);
  ShapeSlopeAt out{w.value};
  if (with_gradient)
    out.gradient = contact_equilibrium_matrix(r.chord, r.alpha) * w.d.transpose() +
                   w.d_alpha * alpha_gradient(r.chord, r.alpha, r.normal);  // ∇w_α (N13)
  return out;
}

DeflectedNormal deflected_normal(const ContactElementData& data, const ContactResponse& r) {
  const ChordFrameLaw& law = r.law;
  const double Y = r.forces[3], N = r.forces[0];
  const Slope w = shape_slope(data, r, law, law_rates(law, r.deformations.segment<2>(1), Y));
  const Vector2d e(r.chord.cos, r.chord.sin), n(-r.chord.sin, r.chord.cos);
  DeflectedNormal out;
  out.slope = w.value / r.chord.length;          // N3
  out.direction = n - out.slope * e;              // N4
  out.axial_share = -out.slope * Y;
  out.axial_force_i = N + (1.0 - r.alpha) * out.axial_share;  // N6
  out.axial_force_j = N - r.alpha * out.axial_share;
  return out;
}

ContactResponse deflected_normal_response(const ContactElementData& data, const Vector9& d, double previous_rotation,
                                          bool with_tangent) {
  // α, δy_c and S as the paper's element measures them (N5); its J S, tangent and point load.
  ContactResponse r = chord_frame_parts(data, d, previous_rotation, with_tangent);
  const ChordFrameLaw& law = r.law;
  const double Y = r.forces[3], c = law.connected.compliance;
  const LawRates rates = law_rates(law, r.deformations.segment<2>(1), Y);
  const Slope w = shape_slope(data, r, law, rates);
  const double T = Y * w.value;
  const Vector2d e(r.chord.cos, r.chord.sin), n(-r.chord.sin, r.chord.cos);
  r.force_per_Y = (n - (w.value / r.chord.length) * e).norm();  // |ν|, N3–N4
  const Vector9 g = alpha_gradient(r.chord, r.alpha, r.normal);
  r.nodal_forces -= T * g;  // N8: J_ν S = J S − T ∂α/∂x
  const Vector9 point_chord = r.point_u;
  r.point_u -= w.value * g;  // J_ν (0, h, 1)ᵀ
  if (!with_tangent) {
    if (data.friction.mu != 0.0) add_friction(data, w.value, Vector9::Zero(), false, r);
    return r;
  }

  // N14: K = K_chord − ∂α/∂x (∇T)ᵀ − T ∂²α, ∇T = w_α ∇Y + Y ∇w_α; N15 splits it.
  const Vector9 dw = contact_equilibrium_matrix(r.chord, r.alpha) * w.d.transpose() + w.d_alpha * g;  // ∇w_α
  // = sym(g, −(w/c) p + (w²/2c) g − Y ∇w_α) − T ∂²α, p the chord's point_u, sym(x, y) = x yᵀ + y xᵀ.
  add_symmetric(r.symmetric_tangent, g, (-w.value / c) * point_chord + (0.5 * w.value * w.value / c) * g - Y * dw);
  add_alpha_hessian(r.symmetric_tangent, -T, r.chord, r.alpha, r.normal);
  if (data.sliding_term) {
    r.sliding_u += (w.value / c) * r.point_u - w.value * rates.dY_dalpha * g + Y * dw;
    r.sliding_v = g;
  }
  if (data.friction.mu != 0.0) add_friction(data, w.value, dw, true, r);
  r.tangent = r.symmetric_tangent + r.sliding_u * r.sliding_v.transpose();
  if (data.friction.mu != 0.0) r.tangent.noalias() += r.friction_u * r.friction_v.transpose();
  return r;
}

}  // namespace tsm::contact
