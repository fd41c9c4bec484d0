#include "tsmframe/assembly/contact_assembly.hpp"

#include "tsmframe/contact/contact_response.hpp"

namespace tsm::assembly {

std::array<int, 9> contact_dofs(const Element& e, int node) {
  std::array<int, 9> g;
  for (int d = 0; d < dofs_per_node; ++d) {
    g[d] = dofs_per_node * e.start + d;
    g[3 + d] = dofs_per_node * e.end + d;
    g[6 + d] = dofs_per_node * node + d;
  }
  return g;
}

std::vector<ContactDirection> contact_directions(const Model& model, const DofMap& dofs,
                                                 const Eigen::VectorXd& displacements, const std::vector<double>& rotations,
                                                 const std::vector<contact::ActiveContact>& contacts) {
  std::vector<ContactDirection> directions;
  directions.reserve(contacts.size());
  for (const contact::ActiveContact& a : contacts) {
    const std::array<int, 9> g = contact_dofs(model.elements[a.element], a.node);
    const contact::ContactResponse r = contact::contact_response(a.data, gather(displacements, g), rotations[a.element], false);
    ContactDirection d;
    for (int k = 0; k < 9; ++k) d.equation[k] = dofs.equation(g[k]);
    d.u = r.point_u;
    d.stiffness = r.point_stiffness;
    d.Y = r.forces[3];
    directions.push_back(d);
  }
  return directions;
}

}  // namespace tsm::assembly
