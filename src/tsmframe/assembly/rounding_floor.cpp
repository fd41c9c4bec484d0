#include "tsmframe/assembly/rounding_floor.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "tsmframe/contact/contact_response.hpp"
#include "tsmframe/element/beam_element.hpp"

namespace tsm::assembly {

ContactRounding contact_rounding(const contact::ActiveContact& a, const Eigen::Matrix<double, 9, 1>& d, double rotation) {
  constexpr double eps = std::numeric_limits<double>::epsilon();
  // The beam part as for the plain element, plus Y's: the error of δy_c − w (about ε times the
  // coordinates involved) divided by the compliance.
  const contact::ContactResponse r = contact::contact_response(a.data, d, rotation, false);
  const element::BeamResponse plain = element::beam_response(a.data.initial, a.data.k0, d.head<6>(), rotation, false);
  const element::RoundOffFloor f = element::round_off_floor(a.data.initial, a.data.k0, d.head<6>(), plain);
  const contact::PointLoadLaw law = contact::point_load_law(a.data.section, a.data.initial.length, r.alpha, a.data.edge, a.data.min_compliance);
  const double coordinates = d.head<2>().cwiseAbs().sum() + d.segment<2>(3).cwiseAbs().sum() +
                             d.segment<2>(6).cwiseAbs().sum() + (a.data.contact_start - a.data.initial.start).norm() +
                             a.data.initial.length;
  ContactRounding share;
  share.y_floor = eps * coordinates / law.compliance + eps * std::abs(r.forces[3]);
  const double m_floor = f.moment + std::max(std::abs(law.h_i), std::abs(law.h_j)) * share.y_floor;
  share.force_squared = 4.0 * f.force * f.force + 6.0 * share.y_floor * share.y_floor;
  share.moment_squared = 2.0 * m_floor * m_floor;
  share.compliance = law.compliance;
  // At the floor: the contact's stiffness cap where that binds, else its edge near a beam node.
  const double edge_floor = contact::point_load_law(a.data.section, a.data.initial.length, 0.0, a.data.edge).compliance;
  const bool at_floor = law.compliance <= std::max(edge_floor, a.data.min_compliance) * (1.0 + 1e-12);
  share.at_cap = at_floor && a.data.min_compliance > edge_floor;
  share.at_edge = at_floor && !share.at_cap;
  share.uncapped = a.data.min_compliance == 0.0;
  return share;
}

RoundingFloor rounding_floor(std::array<double, 2> squared, const std::vector<contact::ActiveContact>& contacts,
                             const std::vector<ContactRounding>& shares) {
  auto& [force, moment] = squared;
  RoundingFloor floor;
  for (size_t k = 0; k < contacts.size(); ++k) {
    const ContactRounding& s = shares[k];
    force += s.force_squared;
    moment += s.moment_squared;
    floor.contacts_force += 6.0 * s.y_floor * s.y_floor;
    ++floor.contacts;
    if (s.y_floor > floor.contact_force) {
      floor.contact_node = contacts[k].node;
      floor.contact_force = s.y_floor;
      floor.compliance = s.compliance;
      floor.at_cap = s.at_cap;
      floor.at_edge = s.at_edge;
      floor.uncapped = s.uncapped;
    }
  }
  floor.force = std::sqrt(force);
  floor.moment = std::sqrt(moment);
  floor.contacts_force = std::sqrt(floor.contacts_force);
  return floor;
}

}  // namespace tsm::assembly
