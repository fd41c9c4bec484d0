#include "tsmframe/element/force_law.hpp"

#include <cmath>

namespace tsm::element {

double shear_factor(const SectionStiffness& section, double l0) {
  return 12.0 * section.shear_flexibility / (l0 * l0);  // Eq. 5 (corrected)
}

BasicStiffness basic_stiffness_terms(const SectionStiffness& section, double l0) {
  const double q = shear_factor(section, l0);
  const double f = section.EI / (l0 * (1.0 + q));  // Eq. 4
  return {section.EA / l0, f * (4.0 + q), f * (2.0 - q)};
}

Matrix3 basic_stiffness(const SectionStiffness& section, double l0) {
  return basic_stiffness_terms(section, l0).matrix();
}

Matrix3 released_stiffness(const BasicStiffness& k0, bool at_i, bool at_j) {
  Matrix3 k = k0.matrix();
  if (at_i && at_j) {
    k.bottomRightCorner<2, 2>().setZero();
  } else if (at_i || at_j) {
    const int kept = at_i ? 2 : 1;
    k(kept, kept) = k0.direct - k0.cross * k0.cross / k0.direct;  // static condensation of M = 0
    k(1, 2) = k(2, 1) = 0.0;
    k(3 - kept, 3 - kept) = 0.0;
  }
  return k;
}

Matrix3 connected_stiffness(const BasicStiffness& k0, double flexibility_i, double flexibility_j) {
  const bool hinge_i = std::isinf(flexibility_i), hinge_j = std::isinf(flexibility_j);
  Matrix3 k = released_stiffness(k0, hinge_i, hinge_j);
  if (hinge_i && hinge_j) return k;
  if (hinge_i || hinge_j) {  // the other end's propped-cantilever stiffness, in series with its spring
    const int kept = hinge_i ? 2 : 1;
    k(kept, kept) = 1.0 / (1.0 / k(kept, kept) + (hinge_i ? flexibility_j : flexibility_i));
    return k;
  }
  // (B⁻¹ + F)⁻¹ with B = [d c; c d]: B⁻¹ = [d −c; −c d] / (d² − c²).
  const double det = k0.direct * k0.direct - k0.cross * k0.cross;
  const double a = k0.direct / det + flexibility_i, b = k0.direct / det + flexibility_j, c = -k0.cross / det;
  const double inverse = 1.0 / (a * b - c * c);
  k(1, 1) = b * inverse;
  k(2, 2) = a * inverse;
  k(1, 2) = k(2, 1) = -c * inverse;
  return k;
}

}  // namespace tsm::element
