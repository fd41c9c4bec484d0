#include "tsmframe/contact/contact_force_law.hpp"

#include <algorithm>
#include <cmath>

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

PointLoadLaw point_load_law(const element::SectionStiffness& section, double l0, double alpha, double edge) {
  const double psi = section.shear_flexibility, span = l0 * l0 + 12.0 * psi;
  PointLoadLaw law;
  {
    const double s = std::clamp(alpha, 0.0, 1.0), a = s * l0, b = (1.0 - s) * l0, p = a * b;
    law.h_i = -(b * l0 + 6.0 * psi) * p / (l0 * span);
    law.h_j = (a * l0 + 6.0 * psi) * p / (l0 * span);
    if (alpha >= 0.0 && alpha <= 1.0) {
      law.dh_i = -l0 * ((b * l0 + 6.0 * psi) * (1.0 - 2.0 * s) - p) / span;
      law.dh_j = l0 * (p + (a * l0 + 6.0 * psi) * (1.0 - 2.0 * s)) / span;
    }
  }
  const double s = std::clamp(alpha, 0.0, 1.0), p = s * (1.0 - s) * l0 * l0;
  const double omega = p * p + 3.0 * psi * (l0 * l0 + p) + 36.0 * psi * psi;  // Eq. 9
  const double scale = 3.0 * section.EI * l0 * span;
  law.compliance = p * omega / scale;
  // The floor: an Euler–Bernoulli point at edge·l0 from a beam node, c = δ³(1−δ)³ l0³ / 3EI.
  const double floor = std::pow(edge * (1.0 - edge) * l0, 3) / (3.0 * section.EI);
  if (law.compliance <= floor) {
    law.compliance = floor;
  } else if (alpha >= 0.0 && alpha <= 1.0) {
    law.dcompliance = (1.0 - 2.0 * s) * l0 * l0 * (omega + p * (2.0 * p + 3.0 * psi)) / scale;
  }
  return law;
}

double default_edge() { return 1e-2; }

}  // namespace tsm::contact
