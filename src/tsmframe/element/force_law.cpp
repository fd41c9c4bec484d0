#include "tsmframe/element/force_law.hpp"

namespace tsm::element {

double shear_factor(const SectionStiffness& section, double l0) {
  return 12.0 * section.shear_flexibility / (l0 * l0);  // Eq. 5 (corrected)
}

Matrix3 basic_stiffness(const SectionStiffness& section, double l0) {
  const double q = shear_factor(section, l0);
  const double f = section.EI / (l0 * (1.0 + q));  // Eq. 4
  Matrix3 k = Matrix3::Zero();
  k(0, 0) = section.EA / l0;
  k(1, 1) = f * (4.0 + q);
  k(1, 2) = f * (2.0 - q);
  k(2, 1) = k(1, 2);
  k(2, 2) = k(1, 1);
  return k;
}

}  // namespace tsm::element
