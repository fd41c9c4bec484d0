#include "tsmframe/assembly/contact_assembly.hpp"

#include "tsmframe/contact/contact_response.hpp"
#include "tsmframe/util/parallel_for.hpp"

namespace tsm::assembly {

std::vector<int> contact_dofs(const Element& e, const contact::ActiveContact& contact) {
  std::vector<int> g;
  contact_dofs(e, contact, g);
  return g;
}

void contact_dofs(const Element& e, const contact::ActiveContact& contact, std::vector<int>& g) {
  g.resize(dofs_per_node * (2 + contact.size()));
  for (int d = 0; d < dofs_per_node; ++d) {
    g[d] = dofs_per_node * e.start + d;
    g[3 + d] = dofs_per_node * e.end + d;
    for (int p = 0; p < contact.size(); ++p) g[6 + 3 * p + d] = dofs_per_node * contact.points[p].node + d;
  }
}

Eigen::VectorXd gather(const Eigen::VectorXd& displacements, const std::vector<int>& dofs) {
  Eigen::VectorXd d;
  gather(displacements, dofs, d);
  return d;
}

void gather(const Eigen::VectorXd& displacements, const std::vector<int>& dofs, Eigen::VectorXd& d) {
  d.resize(static_cast<Eigen::Index>(dofs.size()));
  for (size_t a = 0; a < dofs.size(); ++a) d[static_cast<Eigen::Index>(a)] = displacements[dofs[a]];
}

void contact_element_response(const Model& model, const contact::ActiveContact& a, const Eigen::VectorXd& displacements,
                      const std::vector<double>& previous_rotations, bool with_tangent, contact::MultiPointResponse& response) {
  thread_local std::vector<int> g;  // per thread: the responses are formed in parallel
  thread_local Eigen::VectorXd d;
  contact_dofs(model.elements[a.element], a, g);
  gather(displacements, g, d);
  contact::active_contact_response(a, d, previous_rotations[a.element], with_tangent, response);
}

void contact_element_response(const Model& model, const contact::ActiveContact& a, const Eigen::VectorXd& displacements,
                      const std::vector<double>& previous_rotations, bool with_tangent, contact::ContactResponse& response) {
  const Element& e = model.elements[a.element];
  contact::Vector9 d;
  d << element_displacements(displacements, e.start, e.end),
      displacements.segment<dofs_per_node>(dofs_per_node * a.points.front().node);
  response = contact::contact_response(a.data.front(), d, previous_rotations[a.element], with_tangent);
}

void keep(const contact::ActiveContact& contact, const contact::ContactResponse& r, std::uint64_t id,
          KeptPointResponse& kept) {
  kept.evaluation = id;
  kept.element = contact.element;
  kept.offset = contact.data.front().offset;
  kept.normal = contact.data.front().normal;
  kept.chord = r.chord;
  kept.alpha = r.alpha;
  kept.force_per_Y = r.force_per_Y;
  kept.forces = r.forces;
  kept.nodal_forces = r.nodal_forces;
  kept.sliding_u = r.sliding_u;
  kept.sliding_v = r.sliding_v;
  int pair = 0;
  for (int p = 0; p < 3; ++p)
    for (int q = p; q < 3; ++q) kept.blocks[pair++] = r.symmetric_tangent.block<3, 3>(3 * p, 3 * q);
}

std::vector<ContactDirection> contact_directions(const Model& model, const DofMap& dofs, const NodalFrames& frames,
                                                 const Eigen::VectorXd& displacements, const std::vector<double>& rotations,
                                                 const std::vector<contact::ActiveContact>& contacts) {
  // Each contact's points' directions have their places (`first`), formed in parallel.
  std::vector<size_t> first(contacts.size() + 1, 0);
  for (size_t i = 0; i < contacts.size(); ++i) first[i + 1] = first[i] + static_cast<size_t>(contacts[i].size());
  std::vector<ContactDirection> directions(first.back());
  util::parallel_for_dynamic(size_t{0}, contacts.size(), contacts.size() >= 64, [&](size_t i) {
    const contact::ActiveContact& a = contacts[i];
    const std::vector<int> g = contact_dofs(model.elements[a.element], a);
    std::vector<int> equation(g.size());
    for (size_t k = 0; k < g.size(); ++k) equation[k] = dofs.equation(g[k]);
    const auto put = [&](int p, const auto& u, double stiffness, double Y, Eigen::RowVectorXd row) {
      ContactDirection& d = directions[first[i] + static_cast<size_t>(p)];
      d = {equation, u, stiffness, Y, static_cast<int>(i), std::move(row)};
      frames.to_nodal(g, d.u);
    };
    if (a.size() == 1) {  // the three-node element's fixed-size form, as the evaluation's
      contact::ContactResponse r;
      contact_element_response(model, a, displacements, rotations, false, r);
      put(0, r.point_u, r.point_stiffness, r.forces[3], Eigen::RowVectorXd::Constant(1, r.point_stiffness));
      return;
    }
    const contact::MultiPointResponse r = contact::active_contact_response(a, gather(displacements, g), rotations[a.element], false);
    for (int p = 0; p < a.size(); ++p) put(p, r.point_u.col(p), r.point_stiffness(p, p), r.forces[3 + p], r.point_stiffness.row(p));
  });
  return directions;
}

}  // namespace tsm::assembly
