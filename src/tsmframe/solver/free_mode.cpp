#include "tsmframe/solver/free_mode.hpp"

#include <algorithm>
#include <cmath>

namespace tsm::solver {
namespace {

// The shift: this fraction of the tangent's largest diagonal entry. Each inverse iteration then
// shrinks the other modes against the null one by at least their eigenvalue over the shift
// (even 1e-6 of the largest in a slender fine mesh: 10³ per iteration).
constexpr double shift_fraction = 1e-9;
constexpr int iterations = 6;
// A node moves "most" where its translation is at least this fraction of the largest one (a
// rigid part's nodes all do; along a column turning about its foot, only its top).
constexpr double moving_fraction = 0.9;

}  // namespace

Eigen::VectorXd null_vector(BlockMatrix& K, LinearSolver& solver, int free_count, double within_shifts) {
  double largest = 0.0;
  for (int c = 0; c < K.size; ++c) largest = std::max(largest, K.value[K.column[c]].diagonal().cwiseAbs().maxCoeff());
  if (!(largest > 0.0) || free_count == 0) return {};
  const double shift = shift_fraction * largest;
  for (int c = 0; c < K.size; ++c) K.value[K.column[c]].diagonal().array() += shift;  // the diagonal block comes first
  if (!solver.factorize(K)) return {};
  Eigen::VectorXd x(free_count);
  for (int k = 0; k < free_count; ++k) x[k] = 1.0 + 0.5 * std::sin(1.0 + k);  // touches every mode
  x.normalize();
  double eigenvalue = INFINITY;
  for (int round = 0; round < iterations; ++round) {
    Eigen::VectorXd y = solver.solve(x);
    const double norm = y.norm();
    if (!std::isfinite(norm) || norm == 0.0) return {};
    eigenvalue = 1.0 / norm - shift;  // ‖(K + σI)⁻¹ x‖ = 1 / (μ + σ) along an eigenvector
    x = y / norm;
  }
  return std::abs(eigenvalue) <= within_shifts * shift ? x : Eigen::VectorXd();
}

void name_free_motion(const Model& model, const Eigen::VectorXd& mode, StepFailure& failure) {
  failure.reason = StepFailure::Reason::mechanism;
  double largest = 0.0;
  for (int k = 0; k < model.node_count(); ++k) largest = std::max(largest, mode.segment<2>(dofs_per_node * k).norm());
  failure.moving_nodes.clear();
  failure.moving_count = 0;
  failure.moving_direction.setZero();
  if (largest <= 1e-6 * mode.cwiseAbs().maxCoeff()) {  // nothing translates: a node turns
    int turning = 0;
    for (int k = 0; k < model.node_count(); ++k)
      if (std::abs(mode[dofs_per_node * k + rz]) > std::abs(mode[dofs_per_node * turning + rz])) turning = k;
    failure.moving_nodes = {turning};
    failure.moving_count = 1;
    failure.turning_only = true;
    return;
  }
  bool common = true;
  for (int k = 0; k < model.node_count(); ++k) {
    const Eigen::Vector2d u = mode.segment<2>(dofs_per_node * k);
    if (u.norm() < moving_fraction * largest) continue;
    ++failure.moving_count;
    failure.moving_nodes.push_back(k);
    const Eigen::Vector2d along = u.normalized() * (u.dot(failure.moving_direction) < 0.0 ? -1.0 : 1.0);
    if (failure.moving_direction.isZero()) failure.moving_direction = along;
    else if (std::abs(along.x() * failure.moving_direction.y() - along.y() * failure.moving_direction.x()) > 1e-3) common = false;
  }
  if (!common) failure.moving_direction.setZero();
  std::sort(failure.moving_nodes.begin(), failure.moving_nodes.end(),
            [&](int a, int b) { return model.nodes[a].id < model.nodes[b].id; });
  if (failure.moving_nodes.size() > 3) failure.moving_nodes.resize(3);
}

}  // namespace tsm::solver
