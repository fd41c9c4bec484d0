#include "tsmframe/assembly/dof_map.hpp"

#include <optional>
#include <utility>

#include "tsmframe/assembly/elimination_order.hpp"
#include "tsmframe/model/resting_contact.hpp"
#include "tsmframe/util/first_touch.hpp"

namespace tsm::assembly {

DofMap::DofMap(const Model& model) {
  const int n = model.node_count();
  // Contacts resting from the start join their node to the element they rest on: ordered as if
  // joined by an element. A mat lying on a beam, 1,000 nodes on 3,000 elements, ordered as two
  // separate chains filled in completely once its contacts joined them (minutes in a dense block).
  std::vector<std::pair<int, int>> resting;
  for (const ContactSpec& spec : model.contacts)
    if (const std::optional<RestingContact> rest = resting_contact(model, spec)) {
      const Element& e = model.elements[rest->element];
      resting.emplace_back(spec.node, e.start);
      resting.emplace_back(spec.node, e.end);
    }
  const std::vector<int> order = elimination_order(node_graph(model, resting));

  util::assign_touched(equation_, model.dof_count(), -1);
  util::assign_touched(node_block_, n, -1);
  util::reserve_touched(free_dofs_, model.dof_count());  // exact sizes below: no growth by doubling
  util::reserve_touched(block_node_, n);

  for (int k = 0; k < n; ++k) {
    const int node = order[k];
    bool free = false;
    for (int d = 0; d < dofs_per_node; ++d) free = free || !model.constrained[dofs_per_node * node + d];
    if (!free) continue;
    node_block_[node] = static_cast<int>(block_node_.size());
    block_node_.push_back(node);
    for (int d = 0; d < dofs_per_node; ++d) {
      const int dof = dofs_per_node * node + d;
      if (model.constrained[dof]) continue;
      equation_[dof] = static_cast<int>(free_dofs_.size());
      free_dofs_.push_back(dof);
    }
  }
  free_dofs_.shrink_to_fit();
  block_node_.shrink_to_fit();
}

}  // namespace tsm::assembly
