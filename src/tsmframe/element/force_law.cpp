#include "tsmframe/element/force_law.hpp"

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

}  // namespace tsm::element
