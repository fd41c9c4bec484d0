#include "tsmframe/assembly/dof_map.hpp"

#include "tsmframe/assembly/elimination_order.hpp"
#include "tsmframe/util/first_touch.hpp"

namespace tsm::assembly {

DofMap::DofMap(const Model& model) {
  const int n = model.node_count();
  const std::vector<int> order = elimination_order(node_graph(model));

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
