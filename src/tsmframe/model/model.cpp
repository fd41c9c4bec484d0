#include "tsmframe/model/model.hpp"

#include <set>

namespace tsm {

const char* dof_name(int dof) {
  switch (dof) {
    case ux: return "ux";
    case uy: return "uy";
    default: return "rz";
  }
}

const char* theory_name(BeamTheory theory) {
  return theory == BeamTheory::timoshenko ? "timoshenko" : "euler-bernoulli";
}

int Model::node_index(int id) const {
  for (int k = 0; k < node_count(); ++k)
    if (nodes[k].id == id) return k;
  return -1;
}

std::vector<int> Model::moved_dofs() const {
  if (!stages.empty()) {  // every stage reports the dofs any stage prescribes
    std::set<int> prescribed;
    for (const Stage& stage : stages)
      for (const PrescribedTarget& p : stage.prescribed) prescribed.insert(p.dof);
    return {prescribed.begin(), prescribed.end()};
  }
  if (!stage_moved_dofs.empty()) return stage_moved_dofs;
  std::vector<int> dofs;
  for (Eigen::Index d = 0; d < reference_prescribed.size(); ++d)
    if (reference_prescribed[d] != 0.0) dofs.push_back(static_cast<int>(d));
  return dofs;
}

}  // namespace tsm
