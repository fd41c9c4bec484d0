#include "tsmframe/assembly/dof_map.hpp"

#include "tsmframe/assembly/elimination_order.hpp"

namespace tsm::assembly {

DofMap::DofMap(const Model& model) : equation_(model.dof_count(), -1), node_block_(model.node_count(), -1) {
  const int n = model.node_count();
  const std::vector<int> order = elimination_order(node_graph(model));

  free_dofs_.reserve(model.dof_count());  // exact sizes below: no growth by doubling
  block_node_.reserve(n);

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
