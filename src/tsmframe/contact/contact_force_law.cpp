#include "tsmframe/contact/contact_force_law.hpp"

#include <array>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>

#include "tsmframe/element/deflected_shape.hpp"

namespace tsm::contact {

element::Matrix3 contact_bending_stiffness(const element::SectionStiffness& section, double l0, double alpha) {
  const double a = alpha * l0, b = (1.0 - alpha) * l0, psi = section.shear_flexibility;
  const double omega = a * b * a * b + 3.0 * psi * (l0 * l0 + a * b) + 36.0 * psi * psi;  // Eq. 9
  const double f = section.EI / (l0 * omega);
  element::Matrix3 k;
  // Eq. 7 (its M_i–θ_j entry corrected); Ψ = 0 gives Eq. 6.
  k(0, 0) = f * (4.0 * omega + 3.0 * a * b * b * b - 108.0 * psi * psi);
  k(1, 1) = f * (4.0 * omega + 3.0 * a * a * a * b - 108.0 * psi * psi);
  k(0, 1) = k(1, 0) = f * (9.0 * psi * (l0 * l0 - a * b) - omega);
  k(0, 2) = k(2, 0) = -f * 3.0 * l0 * (b * l0 + 6.0 * psi);
  k(1, 2) = k(2, 1) = f * 3.0 * l0 * (a * l0 + 6.0 * psi);
  k(2, 2) = f * 3.0 * l0 * l0 * (l0 * l0 + 12.0 * psi) / (a * b);
  return k;
}

std::array<double, 2> point_load_moments(const element::SectionStiffness& section, double l0, double alpha) {
  // Maxwell–Betti: the fixed-end moment of a unit point load at s is minus the deflection at s
  // per unit end rotation, h = −N(s) (element/deflected_shape).
  const element::RotationShape N = element::rotation_shape(section, l0, std::clamp(alpha, 0.0, 1.0));
  return {-N.i, -N.j};
}

PointLoadLaw point_load_law(const element::SectionStiffness& section, double l0, double alpha, double edge,
                            double min_compliance) {
  const double psi = section.shear_flexibility, span = l0 * l0 + 12.0 * psi;
  PointLoadLaw law;
  {
    const std::array<double, 2> h = point_load_moments(section, l0, alpha);
    law.h_i = h[0];
    law.h_j = h[1];
    if (alpha >= 0.0 && alpha <= 1.0) {
      const element::RotationShape dN = element::rotation_shape_slope(section, l0, alpha);
      law.dh_i = -dN.i;
      law.dh_j = -dN.j;
    }
  }
  const double s = std::clamp(alpha, 0.0, 1.0), p = s * (1.0 - s) * l0 * l0;
  const double omega = p * p + 3.0 * psi * (l0 * l0 + p) + 36.0 * psi * psi;  // Eq. 9
  const double scale = 3.0 * section.EI * l0 * span;
  law.compliance = p * omega / scale;
  // The floor: an Euler–Bernoulli point at edge·l0 from a beam node, c = δ³(1−δ)³ l0³ / 3EI.
  const double floor = std::max(std::pow(edge * (1.0 - edge) * l0, 3) / (3.0 * section.EI), min_compliance);
  if (law.compliance <= floor) {
    law.compliance = floor;
  } else if (alpha >= 0.0 && alpha <= 1.0) {
    law.dcompliance = (1.0 - 2.0 * s) * l0 * l0 * (omega + p * (2.0 * p + 3.0 * psi)) / scale;
  }
  return law;
}

ConnectedLaw connected_law(const PointLoadLaw& law, const Eigen::Matrix2d& k_plain, double flexibility_i,
                           double flexibility_j) {
  const double flexibility[2] = {flexibility_i, flexibility_j};
  Eigen::Vector2d h(law.h_i, law.h_j), dh(law.dh_i, law.dh_j);
  double c = law.compliance, dc = law.dcompliance;
  Eigen::Matrix2d k = k_plain;
  // Hinges, one end at a time (static condensation of M_r = 0 for θ_e,r): h_s −= k_sr h_r / k_rr,
  // c += h_r² / k_rr, k −= k_·r k_r·ᵀ / k_rr, which leaves row and column r zero.
  for (int r = 0; r < 2; ++r) {
    if (!std::isinf(flexibility[r]) || !(k(r, r) > 0.0)) continue;
    const Eigen::Vector2d column = k.col(r);
    const double krr = k(r, r);
    c += h[r] * h[r] / krr;
    dc += 2.0 * h[r] * dh[r] / krr;
    h -= column * (h[r] / krr);
    dh -= column * (dh[r] / krr);
    k -= column * column.transpose() / krr;
    h[r] = dh[r] = 0.0;  // exactly, not by cancellation
  }
  // Springs on the other ends: θ_node = θ_e + F M gives M = A k θ_node + A h Y, A = (I + k F)⁻¹,
  // and c' = c + hᵀ F A h (F A is symmetric); d/dα: A dh and dc + 2 (F A h)ᵀ dh.
  Eigen::Matrix2d F = Eigen::Matrix2d::Zero();
  for (int r = 0; r < 2; ++r)
    if (!std::isinf(flexibility[r])) F(r, r) = flexibility[r];
  ConnectedLaw out;
  out.law = law;
  const Eigen::Matrix2d A = (Eigen::Matrix2d::Identity() + k * F).inverse();
  const Eigen::Vector2d g = A * h, dg = A * dh, Fg = F * g;
  out.k_plain = A * k;
  out.k_plain(0, 1) = out.k_plain(1, 0) = 0.5 * (out.k_plain(0, 1) + out.k_plain(1, 0));  // symmetric up to rounding
  out.law.h_i = g[0];
  out.law.h_j = g[1];
  out.law.dh_i = dg[0];
  out.law.dh_j = dg[1];
  out.law.compliance = c + h.dot(Fg);
  out.law.dcompliance = dc + 2.0 * Fg.dot(dh);
  return out;
}

double default_edge() { return 1e-2; }

}  // namespace tsm::contact
