#include "tsmframe/assembly/dof_map.hpp"

#include <Eigen/OrderingMethods>
#include <Eigen/SparseCore>
#include <algorithm>

namespace tsm::assembly {

NodeGraph node_graph(const Model& model) {
  const int n = model.node_count();
  NodeGraph g;
  g.start.assign(n + 1, 0);
  for (int k = 0; k < n; ++k) g.start[k + 1] = 1;  // itself
  for (const Element& e : model.elements) {
    ++g.start[e.start + 1];
    ++g.start[e.end + 1];
  }
  for (int k = 0; k < n; ++k) g.start[k + 1] += g.start[k];
  g.neighbours.resize(g.start[n]);
  std::vector<int> fill(g.start.begin(), g.start.end() - 1);
  for (int k = 0; k < n; ++k) g.neighbours[fill[k]++] = k;
  for (const Element& e : model.elements) {
    g.neighbours[fill[e.start]++] = e.end;
    g.neighbours[fill[e.end]++] = e.start;
  }
  // Sort and drop duplicates (two elements between the same nodes) in place, compacting.
  int write = 0;
  for (int k = 0; k < n; ++k) {
    const int begin = g.start[k], end = g.start[k + 1];
    std::sort(g.neighbours.begin() + begin, g.neighbours.begin() + end);
    const int first = write;
    for (int p = begin; p < end; ++p)
      if (p == begin || g.neighbours[p] != g.neighbours[p - 1]) g.neighbours[write++] = g.neighbours[p];
    g.start[k] = first;
  }
  g.start[n] = write;
  g.neighbours.resize(write);
  g.neighbours.shrink_to_fit();
  return g;
}

DofMap::DofMap(const Model& model) : equation_(model.dof_count(), -1), node_block_(model.node_count(), -1) {
  const int n = model.node_count();
  // Approximate minimum degree on the node graph: the elimination order of the nodes.
  const NodeGraph g = node_graph(model);
  Eigen::SparseMatrix<double, Eigen::ColMajor, int> pattern(n, n);
  pattern.resizeNonZeros(static_cast<Eigen::Index>(g.neighbours.size()));
  std::copy(g.start.begin(), g.start.end(), pattern.outerIndexPtr());
  std::copy(g.neighbours.begin(), g.neighbours.end(), pattern.innerIndexPtr());
  std::fill(pattern.valuePtr(), pattern.valuePtr() + pattern.nonZeros(), 1.0);
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> order;
  Eigen::AMDOrdering<int>()(pattern, order);

  free_dofs_.reserve(model.dof_count());  // exact sizes below: no growth by doubling
  block_node_.reserve(n);

  for (int k = 0; k < n; ++k) {
    const int node = order.indices()[k];
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
