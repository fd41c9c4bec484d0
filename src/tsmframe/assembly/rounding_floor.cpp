#include "tsmframe/assembly/rounding_floor.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "tsmframe/contact/active_contact.hpp"
#include "tsmframe/element/beam_element.hpp"

namespace tsm::assembly {

ContactRounding contact_rounding(const contact::ActiveContact& a, const Eigen::VectorXd& d, double rotation) {
  constexpr double eps = std::numeric_limits<double>::epsilon();
  // The beam part as for the plain element, plus each point's Y: the error of δy_p − w (about ε
  // times the coordinates involved) divided by its compliance.
  const contact::ContactElementData& beam = a.data.front();
  const contact::MultiPointResponse r = contact::active_contact_response(a, d, rotation, false);
  const element::BeamResponse plain = element::beam_response(beam.initial, beam.k0, d.head<6>(), rotation, false);
  const element::RoundOffFloor f = element::round_off_floor(beam.initial, beam.k0, d.head<6>(), plain);
  ContactRounding share;
  double m_floor = f.moment;
  for (int p = 0; p < a.size(); ++p) {
    const contact::ContactElementData& point = a.data[p];
    const contact::PointLoadLaw law =
        contact::point_load_law(point.section, point.initial.length, r.alpha[p], point.edge, point.min_compliance);
    const double coordinates = d.head<2>().cwiseAbs().sum() + d.segment<2>(3).cwiseAbs().sum() +
                               d.segment<2>(6 + 3 * p).cwiseAbs().sum() + (point.contact_start - point.initial.start).norm() +
                               point.initial.length;
    const double y_floor = eps * coordinates / law.compliance + eps * std::abs(r.forces[3 + p]);
    m_floor += std::max(std::abs(law.h_i), std::abs(law.h_j)) * y_floor;
    share.points_squared += 6.0 * y_floor * y_floor;
    if (p > 0 && !(y_floor > share.y_floor)) continue;
    share.node = a.points[p].node;
    share.y_floor = y_floor;
    share.compliance = law.compliance;
    // At the floor: the contact's stiffness cap where that binds, else its edge near a beam node.
    const double edge_floor = contact::point_load_law(point.section, point.initial.length, 0.0, point.edge).compliance;
    const bool at_floor = law.compliance <= std::max(edge_floor, point.min_compliance) * (1.0 + 1e-12);
    share.at_cap = at_floor && point.min_compliance > edge_floor;
    share.at_edge = at_floor && !share.at_cap;
    share.uncapped = point.min_compliance == 0.0;
  }
  share.force_squared = 4.0 * f.force * f.force + share.points_squared;
  share.moment_squared = 2.0 * m_floor * m_floor;
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
    floor.contacts_force += s.points_squared;
    floor.contacts += contacts[k].size();
    if (s.y_floor > floor.contact_force) {
      floor.contact_node = s.node;
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
