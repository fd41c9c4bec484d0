#include "tsmframe/contact/contact_geometry.hpp"

#include <algorithm>
#include <limits>

#include "tsmframe/contact/multi_point_law.hpp"
#include "tsmframe/model/candidate_groups.hpp"

namespace tsm::contact {

ContactGeometry::ContactGeometry(const Model& model) : model_(model) {
  if (model.contacts.empty()) return;  // nothing to track: no per-element data for big contact-free models
  const int n_elements = static_cast<int>(model.elements.size());
  initial_.reserve(n_elements);
  for (const Element& e : model.elements)
    initial_.push_back(element::initial_chord(model.nodes[e.start].position, model.nodes[e.end].position));
  node_start_.assign(model.node_count() + 1, 0);
  for (const Element& e : model.elements) {
    ++node_start_[e.start + 1];
    ++node_start_[e.end + 1];
  }
  for (int k = 0; k < model.node_count(); ++k) node_start_[k + 1] += node_start_[k];
  node_elements_.resize(node_start_.back());
  std::vector<int> fill(node_start_.begin(), node_start_.end() - 1);
  for (int k = 0; k < n_elements; ++k) {
    node_elements_[fill[model.elements[k].start]++] = k;
    node_elements_[fill[model.elements[k].end]++] = k;
  }
  touch_tolerance_ = 1e-10 * model.size;
  const CandidateGroups groups = candidate_groups(model.contacts);
  for (const int first : groups.first) tables_.push_back(std::make_shared<const CandidateTable>(table_of(model.contacts[first])));
  contacts_.reserve(model.contacts.size());
  for (size_t k = 0; k < model.contacts.size(); ++k)
    contacts_.push_back(candidates_of(model.contacts[k], *tables_[groups.of_contact[k]]));
  std::vector<char> candidate(n_elements, 0);
  for (const auto& table : tables_)
    for (const int f : table->elements) candidate[f] = 1;
  for (int k = 0; k < n_elements; ++k)
    if (candidate[k]) candidate_elements_.push_back(k);
  if (std::any_of(model.contacts.begin(), model.contacts.end(), [](const ContactSpec& c) { return c.friction > 0.0; })) {
    std::vector<double> along(model.member_count, 0.0);  // a member's elements run from its start, in order
    arc_start_.resize(n_elements);
    for (int k = 0; k < n_elements; ++k) {
      arc_start_[k] = along[model.elements[k].member];
      along[model.elements[k].member] += initial_[k].length;
    }
  }
}

CandidateTable ContactGeometry::table_of(const ContactSpec& c) const {
  const int n_elements = static_cast<int>(model_.elements.size());
  CandidateTable t;
  t.index.assign(n_elements, -1);
  std::vector<bool> in_set(model_.member_count, false);
  for (int m : c.members) in_set[m] = true;
  for (int k = 0; k < n_elements; ++k) {
    const Element& e = model_.elements[k];
    if (!in_set[e.member]) continue;
    t.index[k] = static_cast<int>(t.elements.size());
    t.elements.push_back(k);
    double psi = e.section.shear_flexibility;  // the touched element's theory, unless the contact names one
    if (c.theory == BeamTheory::euler_bernoulli) psi = 0.0;
    if (c.theory == BeamTheory::timoshenko) psi = c.member_shear_flexibility[e.member];
    t.shear_flexibility.push_back(psi);
    t.longest = std::max(t.longest, initial_[k].length);
  }
  t.links.reserve(2 * t.elements.size());
  for (const int f : t.elements)
    for (const int node : {model_.elements[f].start, model_.elements[f].end}) t.links.push_back(link(t, f, node));
  return t;
}

CandidateLink ContactGeometry::link(const CandidateTable& table, int element, int node) const {
  // The side left of each element's direction away from the node (n is e turned +90°) is the
  // other's right where two meet (sides.hpp, across).
  const auto left_side = [&](int f) { return model_.elements[f].start == node ? 1 : -1; };
  int count = 0, other = -1;
  for (const int g : node_elements(node))
    if (table.index[g] >= 0) {
      ++count;
      if (g != element) other = g;
    }
  if (count < 2 || other < 0) return {};
  if (count > 2) return {CandidateLink::joint, 0};
  return {table.index[other], left_side(element) * -left_side(other)};
}

ContactCandidates ContactGeometry::candidates_of(const ContactSpec& c, const CandidateTable& table) const {
  ContactCandidates s;
  s.node = c.node;
  s.candidates = table.elements;
  s.candidate_index = table.index;
  s.shear_flexibility = table.shear_flexibility;
  s.links = table.links;
  s.longest_candidate = table.longest;
  s.gap = c.gap;
  s.edge = c.edge;
  s.max_stiffness_ratio = c.max_stiffness_ratio;
  for (const int e : node_elements(c.node)) {
    const element::SectionStiffness& section = model_.elements[e].section;
    s.own.push_back({std::cos(initial_[e].angle), std::sin(initial_[e].angle), section.EA, section.EI, initial_[e].length});
  }
  s.sliding_term = c.sliding_tangent;
  s.friction = c.friction;
  s.frame = c.frame;
  s.normal = c.normal;
  return s;
}

double ContactGeometry::cap_compliance(const ContactCandidates& contact, int element, bool along_chord) const {
  const double angle = initial_[element].angle;
  const Eigen::Vector2d normal = along_chord ? Eigen::Vector2d(std::cos(angle), std::sin(angle))
                                             : Eigen::Vector2d(-std::sin(angle), std::cos(angle));
  double stiffest = 0.0;
  for (const ContactCandidates::Own& o : contact.own) {
    const double along = o.cos * normal.x() + o.sin * normal.y();
    const double c2 = along * along;  // the element's axis against the contact's normal
    stiffest = std::max(stiffest, c2 * o.EA / o.l0 + (1.0 - c2) * 12.0 * o.EI / (o.l0 * o.l0 * o.l0));
  }
  return stiffest > 0.0 ? 1.0 / (contact.max_stiffness_ratio * stiffest) : 0.0;
}

double ContactGeometry::edge_of(const ContactCandidates& contact) { return contact.edge >= 0.0 ? contact.edge : default_edge(); }

element::SectionStiffness ContactGeometry::contact_section(const ContactCandidates& contact, int element) const {
  element::SectionStiffness s = model_.elements[element].section;
  s.shear_flexibility = contact.shear_flexibility[contact.candidate_index[element]];
  return s;
}

std::pair<double, double> ContactGeometry::end_flexibilities(int element) const {
  const Element& e = model_.elements[element];
  return {e.release_start ? INFINITY : model_.flexibility_start(e), e.release_end ? INFINITY : model_.flexibility_end(e)};
}

Eigen::Vector2d ContactGeometry::chord_normal(int element, const Eigen::VectorXd& D, const std::vector<double>& rotations) const {
  const element::Chord chord =
      element::current_chord(initial_[element], element_displacements(model_.elements[element], D), rotations[element]);
  return {-chord.sin, chord.cos};
}

NodeOnElement ContactGeometry::locate(const ContactCandidates& contact, int element, const Eigen::VectorXd& D,
                                      const std::vector<double>& rotations, double lowest, double highest,
                                      const ElementLoads* loads) const {
  const Element& e = model_.elements[element];
  const Eigen::Vector2d node = position(contact.node, D);
  const element::Vector6 d = element_displacements(e, D);
  // α first, from the chord alone: a node beyond the span asked for needs no gap (most of a
  // long beam's elements, for each contact node).
  if (const double alpha = alpha_on_element(initial_[element], d, node); alpha < lowest || alpha > highest)
    return {alpha, std::numeric_limits<double>::quiet_NaN()};
  const auto [flexibility_i, flexibility_j] = end_flexibilities(element);
  NodeOnElement where = node_on_element(initial_[element], contact_section(contact, element), d, rotations[element], node,
                                        flexibility_i, flexibility_j);
  if (loads) where.gap -= loaded_deflection(contact, element, where.alpha, loads->on(element));
  return where;
}

double ContactGeometry::loaded_deflection(const ContactCandidates& contact, int element, double alpha,
                                          const std::vector<PointLoad>& loads) const {
  if (loads.empty()) return 0.0;
  const int k = static_cast<int>(loads.size());
  const ContactElementData data = element_data(contact, element, 1);
  Eigen::VectorXd alphas(k + 1);
  Eigen::VectorXd Y(k);
  for (int q = 0; q < k; ++q) alphas[q] = loads[q].alpha, Y[q] = loads[q].Y;
  alphas[k] = alpha;
  MultiPointLaw law = multi_point_law(data.section, data.initial.length, alphas, data.edge, data.min_compliance);
  if (data.connected())
    law = connected_multi_point_law(law, data.k0.bottomRightCorner<2, 2>(), data.flexibility_i, data.flexibility_j).law;
  return law.compliance.row(k).head(k).dot(Y);
}

NodeOnElement ContactGeometry::on_chord(const ContactCandidates& contact, int element, const Eigen::VectorXd& D) const {
  const Element& e = model_.elements[element];
  const element::ChordPlace place = element::place_on_chord(position(e.start, D), position(e.end, D), position(contact.node, D));
  return {place.alpha, place.across};
}

ContactElementData ContactGeometry::element_data(const ContactCandidates& contact, int element, int side) const {
  ContactElementData data;
  data.initial = initial_[element];
  data.section = contact_section(contact, element);
  data.k0 = element::basic_stiffness(data.section, data.initial.length);
  data.contact_start = model_.nodes[contact.node].position;
  data.offset = side * contact.gap;
  data.edge = edge_of(contact);
  data.min_compliance = cap_compliance(contact, element);
  data.sliding_term = contact.sliding_term;
  data.frame = contact.frame;
  data.normal = contact.normal;
  std::tie(data.flexibility_i, data.flexibility_j) = end_flexibilities(element);
  if (contact.friction > 0.0) {  // the anchor is the state's (ContactSet::active_contacts)
    data.friction.mu = contact.friction;
    data.friction.side = side;
    data.friction.arc_start = arc_start_[element];
    data.friction.min_compliance = cap_compliance(contact, element, true);
  }
  return data;
}

}  // namespace tsm::contact
