#pragma once
// Numbering of the free (unknown) dofs. Constrained dofs (fixed or prescribed) get −1. Free
// dofs are numbered node by node in a fill-reducing order (elimination_order: members' paths
// from both ends, the joints by minimum degree, each path before its first joint; computed
// once), so the factorisation needs no permutation of its own.

#include <vector>

#include "tsmframe/assembly/node_graph.hpp"
#include "tsmframe/model/model.hpp"

namespace tsm::assembly {

class DofMap {
 public:
  explicit DofMap(const Model& model);

  int dof_count() const { return static_cast<int>(equation_.size()); }
  int free_count() const { return static_cast<int>(free_dofs_.size()); }
  /// Equation number of a global dof, or −1 if it is constrained.
  int equation(int dof) const { return equation_[dof]; }
  /// Global dof of an equation.
  int dof(int equation) const { return free_dofs_[equation]; }
  const std::vector<int>& free_dofs() const { return free_dofs_; }

  /// Nodes with at least one free dof are the blocks of the tangent, numbered in the
  /// fill-reducing order; the equations run block by block in the same order.
  int block_count() const { return static_cast<int>(block_node_.size()); }
  /// Block of a node, or −1 if all its dofs are constrained.
  int block(int node) const { return node_block_[node]; }
  int block_node(int block) const { return block_node_[block]; }

 private:
  std::vector<int> equation_;
  std::vector<int> free_dofs_;
  std::vector<int> node_block_;
  std::vector<int> block_node_;
};

}  // namespace tsm::assembly
