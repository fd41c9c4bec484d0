#pragma once
// Which nodes an element joins: the graph the ordering and the tangent's pattern are built from.

#include <utility>
#include <vector>

#include "tsmframe/model/model.hpp"

namespace tsm::assembly {

/// Nodes joined to each node by an element, itself included (CSR, sorted, no duplicates).
struct NodeGraph {
  std::vector<int> start;      ///< node k's neighbours are neighbours[start[k] .. start[k+1])
  std::vector<int> neighbours;
};
/// With `extra`: those pairs of nodes joined too (contacts known before the run: DofMap's ordering).
NodeGraph node_graph(const Model& model, const std::vector<std::pair<int, int>>& extra = {});

}  // namespace tsm::assembly
