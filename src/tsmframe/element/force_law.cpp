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

}  // namespace tsm::element
