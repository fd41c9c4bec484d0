#include "tsmframe/model/nodal_frames.hpp"

#include <algorithm>

namespace tsm {

NodalFrames::NodalFrames(const Model& model) {
  if (model.skew_rollers.empty()) return;
  std::vector<SkewRoller> rollers = model.skew_rollers;
  std::sort(rollers.begin(), rollers.end(), [](const SkewRoller& a, const SkewRoller& b) { return a.node < b.node; });
  frame_of_.assign(model.node_count(), -1);
  for (const SkewRoller& r : rollers) {
    frame_of_[r.node] = static_cast<int>(nodes_.size());
    nodes_.push_back(r.node);
    along_.push_back(r.along);
  }
}

Eigen::Matrix3d NodalFrames::frame(int node) const {
  Eigen::Matrix3d T = Eigen::Matrix3d::Identity();
  if (!turned(node)) return T;
  const Eigen::Vector2d& t = along_[frame_of_[node]];
  T.topLeftCorner<2, 2>() << t.x(), -t.y(), t.y(), t.x();  // columns t and n = (−t_y, t_x)
  return T;
}

void NodalFrames::to_global(Eigen::VectorXd& d) const {
  for (size_t k = 0; k < nodes_.size(); ++k) {
    const Eigen::Vector2d& t = along_[k];
    const int base = dofs_per_node * nodes_[k];
    const double a = d[base + ux], b = d[base + uy];  // (t, n) components
    d[base + ux] = t.x() * a - t.y() * b;
    d[base + uy] = t.y() * a + t.x() * b;
  }
}

void NodalFrames::to_nodal(Eigen::VectorXd& f) const {
  for (size_t k = 0; k < nodes_.size(); ++k) {
    const Eigen::Vector2d& t = along_[k];
    const int base = dofs_per_node * nodes_[k];
    const double x = f[base + ux], y = f[base + uy];
    f[base + ux] = t.x() * x + t.y() * y;
    f[base + uy] = -t.y() * x + t.x() * y;
  }
}

void NodalFrames::to_nodal(std::span<const int> dofs, Eigen::Ref<Eigen::VectorXd> f) const {
  if (empty()) return;
  for (size_t a = 0; a + 1 < dofs.size(); ++a) {
    const int node = dofs[a] / dofs_per_node;
    if (dofs[a] % dofs_per_node != ux || dofs[a + 1] != dofs[a] + 1 || !turned(node)) continue;
    const Eigen::Vector2d& t = along_[frame_of_[node]];
    const Eigen::Index i = static_cast<Eigen::Index>(a);
    const double x = f[i], y = f[i + 1];
    f[i] = t.x() * x + t.y() * y;
    f[i + 1] = -t.y() * x + t.x() * y;
  }
}

Eigen::Matrix3d NodalFrames::to_nodal(int node_a, int node_b, const Eigen::Matrix3d& block) const {
  return frame(node_a).transpose() * block * frame(node_b);
}

NodalFrames::Share NodalFrames::row_share(int dof) const {
  const int node = dof / dofs_per_node, d = dof % dofs_per_node;
  if (d == rz || !turned(node)) return {dof, 1.0};
  const Eigen::Vector2d& t = along_[frame_of_[node]];
  return {dofs_per_node * node + ux, t[d]};  // only t carries an equation: n is held
}

}  // namespace tsm
