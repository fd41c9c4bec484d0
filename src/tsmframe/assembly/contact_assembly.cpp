#include "tsmframe/assembly/contact_assembly.hpp"

#include "tsmframe/contact/contact_response.hpp"

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
  for (int k = 0; k < dofs_per_node; ++k) {
    d[k] = displacements[dofs_per_node * e.start + k];
    d[3 + k] = displacements[dofs_per_node * e.end + k];
    d[6 + k] = displacements[dofs_per_node * a.points.front().node + k];
  }
  response = contact::contact_response(a.data.front(), d, previous_rotations[a.element], with_tangent);
}

std::vector<ContactDirection> contact_directions(const Model& model, const DofMap& dofs, const NodalFrames& frames,
                                                 const Eigen::VectorXd& displacements, const std::vector<double>& rotations,
                                                 const std::vector<contact::ActiveContact>& contacts) {
  std::vector<ContactDirection> directions;
  directions.reserve(contacts.size());
  for (const contact::ActiveContact& a : contacts) {
    const std::vector<int> g = contact_dofs(model.elements[a.element], a);
    const contact::MultiPointResponse r =
        contact::active_contact_response(a, gather(displacements, g), rotations[a.element], false);
    std::vector<int> equation(g.size());
    for (size_t k = 0; k < g.size(); ++k) equation[k] = dofs.equation(g[k]);
    for (int p = 0; p < a.size(); ++p) {
      directions.push_back({equation, r.point_u.col(p), r.point_stiffness(p, p), r.forces[3 + p],
                            static_cast<int>(&a - contacts.data()), r.point_stiffness.row(p)});
      frames.to_nodal(g, directions.back().u);
    }
  }
  return directions;
}

}  // namespace tsm::assembly
