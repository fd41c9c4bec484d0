#include "tsmframe/assembly/nodal_springs.hpp"

namespace tsm::assembly {

Eigen::Matrix3d NodalSprings::block(const NodalSpring& s) {
  Eigen::Matrix3d k = Eigen::Matrix3d::Zero();
  if (s.kind == NodalSpring::Kind::rotation) k(rz, rz) = s.stiffness;
  else k.topLeftCorner<2, 2>() = s.stiffness * s.direction * s.direction.transpose();  // k d dᵀ
  return k;
}

void NodalSprings::add_forces(const Eigen::VectorXd& displacements, const std::vector<char>* only, Eigen::VectorXd& out) const {
  for (const NodalSpring& s : model_.springs) {
    if (only && !(*only)[s.node]) continue;
    const int base = dofs_per_node * s.node;
    if (s.kind == NodalSpring::Kind::rotation) {
      out[base + rz] += s.stiffness * displacements[base + rz];  // k θ
    } else {
      const double stretch = s.direction.dot(displacements.segment<2>(base));  // d·u
      out.segment<2>(base) += s.stiffness * stretch * s.direction;
    }
  }
}

}  // namespace tsm::assembly
