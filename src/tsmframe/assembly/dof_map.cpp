#include "tsmframe/assembly/dof_map.hpp"

namespace tsm::assembly {

DofMap::DofMap(const Model& model) : equation_(model.dof_count(), -1) {
  for (int dof = 0; dof < model.dof_count(); ++dof) {
    if (model.constrained[dof]) continue;
    equation_[dof] = static_cast<int>(free_dofs_.size());
    free_dofs_.push_back(dof);
  }
}

}  // namespace tsm::assembly
