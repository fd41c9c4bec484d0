#include "tsmframe/assembly/follower_loads.hpp"

#include <Eigen/Geometry>
#include <utility>

namespace tsm::assembly {
namespace {

/// R(θ) F: a follower point load at its node's rotation θ.
Eigen::Vector2d turned(const FollowerForce& f, const Eigen::VectorXd& displacements) {
  return Eigen::Rotation2Dd(displacements[dofs_per_node * f.node + rz]) * f.force;
}

}  // namespace

FollowerLoads::FollowerLoads(const Model& model, const DofMap& dofs, const NodalFrames& frames)
    : model_(model), dofs_(dofs), frames_(frames) {
  for (const Element& e : model.elements)
    if (const double p = model.pressure(e), dead = model.dead_pressure(e); p != 0.0 || dead != 0.0)
      loads_.push_back({e.start, e.end, p, dead});
  for (const Load& f : loads_) has_dead_ = has_dead_ || f.dead_pressure != 0.0;
  for (const FollowerForce& f : model.follower_forces) has_dead_ = has_dead_ || f.dead;
  if (loads_.empty()) return;
  // c per node, live (per unit λ) and dead: exactly 0 where equal pressures meet (−p/2 + p/2).
  std::vector<Skew> skew(model.node_count());
  for (const Load& f : loads_) {
    skew[f.start].live -= 0.5 * f.pressure;
    skew[f.end].live += 0.5 * f.pressure;
    skew[f.start].dead -= 0.5 * f.dead_pressure;
    skew[f.end].dead += 0.5 * f.dead_pressure;
  }
  for (int node = 0; node < model.node_count(); ++node)
    if (skew[node].live != 0.0 || skew[node].dead != 0.0) skew_.push_back({node, skew[node].live, skew[node].dead});
}

void FollowerLoads::add_loads(const Eigen::VectorXd& displacements, bool dead, Eigen::VectorXd& out) const {
  for (const Load& f : loads_) {
    const double p = dead ? f.dead_pressure : f.pressure;
    if (p == 0.0) continue;
    const Eigen::Vector2d d = model_.nodes[f.end].position + displacements.segment<2>(dofs_per_node * f.end) -
                              model_.nodes[f.start].position - displacements.segment<2>(dofs_per_node * f.start);
    const Eigen::Vector2d half = 0.5 * p * Eigen::Vector2d(d.y(), -d.x());  // −(p/2) R d
    out.segment<2>(dofs_per_node * f.start) += half;
    out.segment<2>(dofs_per_node * f.end) += half;
  }
  for (const FollowerForce& f : model_.follower_forces)
    if (f.dead == dead) out.segment<2>(dofs_per_node * f.node) += turned(f, displacements);
}

void FollowerLoads::reference_load(const Eigen::VectorXd& displacements, Eigen::VectorXd& out) const {
  out = model_.reference_load;
  add_loads(displacements, false, out);
}

void FollowerLoads::dead_load(const Eigen::VectorXd& displacements, Eigen::VectorXd& out) const {
  if (model_.dead_load.size() > 0) out = model_.dead_load;
  else out.setZero(model_.dof_count());
  add_loads(displacements, true, out);
}

void FollowerLoads::skew_terms(double load_factor, const Eigen::VectorXd& displacements,
                               std::vector<linalg::RankOne>& out) const {
  out.clear();
  for (const FollowerForce& f : model_.follower_forces) {
    const int base = dofs_per_node * f.node, theta = dofs_.equation(base + rz);
    const double scale = f.dead ? 1.0 : load_factor;  // a dead force is applied in full
    if (theta < 0 || scale == 0.0) continue;  // a held rotation turns the force by no unknown
    const Eigen::Vector2d P = turned(f, displacements);
    // −λ ∂P/∂θ = −λ Q R(θ) F, Q (x, y) = (−y, x)
    linalg::RankOne term{{dofs_.equation(base + ux), dofs_.equation(base + uy), theta},
                         Eigen::Vector3d(scale * P.y(), -scale * P.x(), 0.0), Eigen::Vector3d(0.0, 0.0, 1.0)};
    const int dofs[3] = {base + ux, base + uy, base + rz};
    frames_.to_nodal(dofs, term.u);  // the rows at a skew roller
    out.push_back(std::move(term));
  }
  for (const Skew& skew : skew_) {
    const int node = skew.node;
    const double c = level(load_factor, skew.live, skew.dead);
    const int u = dofs_.equation(dofs_per_node * node + ux), v = dofs_.equation(dofs_per_node * node + uy);
    if (c == 0.0 || u < 0 || v < 0) continue;  // a held dof carries no equation
    linalg::RankOne term{{u, v}, Eigen::Vector2d(1.0, 0.0), Eigen::Vector2d(0.0, -c)};  // K_uv −= c
    out.push_back(term);
    term.u << 0.0, 1.0;
    term.v << c, 0.0;  // K_vu += c
    out.push_back(term);
  }
}

}  // namespace tsm::assembly
