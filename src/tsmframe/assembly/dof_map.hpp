#pragma once
// Numbering of the free (unknown) dofs; constrained dofs (fixed or prescribed) get −1.

#include <vector>

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

 private:
  std::vector<int> equation_;
  std::vector<int> free_dofs_;
};

}  // namespace tsm::assembly
