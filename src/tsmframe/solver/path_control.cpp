#include "tsmframe/solver/path_control.hpp"

#include <cmath>

namespace tsm::solver {

std::optional<double> least_turning_root(const ArcLengthQuadratic& q, double along_trial, double along_load,
                                         double load_increment, double prescribed_squared) {
  const double disc = q.b * q.b - 4.0 * q.a * q.c;
  if (!(disc >= 0.0)) return std::nullopt;
  // The roots without cancellation (Numerical Recipes' form).
  const double s = -0.5 * (q.b + std::copysign(std::sqrt(disc), q.b));
  const double r1 = s / q.a, r2 = s != 0.0 ? q.c / s : -r1;
  const double dl = load_increment, P2 = prescribed_squared;
  const auto turn = [&](double r) { return along_trial + r * along_load + dl * (dl + r) * P2; };
  return turn(r1) >= turn(r2) ? r1 : r2;
}

void PathControl::begin_step(const PathConstraint& constraint, const State& state) {
  if (constraint.kind == PathConstraint::Kind::arc_length) passes_.free_displacements(state, start_);
  start_load_factor_ = state.load_factor;
}

PathCorrection PathControl::correction(const PathConstraint& constraint, int iteration, const Eigen::VectorXd& a,
                                       const Eigen::VectorXd& b, const State& state) {
  if (constraint.kind == PathConstraint::Kind::arc_length) return arc_length(constraint, iteration, a, b, state);
  // Displacement control: δλ puts the controlled dof on its target, D_k + b_k + δλ a_k = target.
  const int k = constraint.equation;
  if (!(std::abs(a[k]) > 0.0) || !std::isfinite(a[k])) return {0.0, StepFailure::Reason::controlled_dof_immobile};
  return {(constraint.target - state.displacements[passes_.equations().free_dofs[k]] - b[k]) / a[k]};
}

PathCorrection PathControl::arc_length(const PathConstraint& constraint, int iteration, const Eigen::VectorXd& a,
                                       const Eigen::VectorXd& b, const State& state) {
  const double P2 = passes_.equations().prescribed_squared, s2 = constraint.arc_length * constraint.arc_length;
  const double qa = passes_.translation_dot(a, a) + P2;
  if (!(qa > 0.0) || !std::isfinite(qa)) return {0.0, StepFailure::Reason::arc_length_undefined};
  if (iteration == 1) {  // predictor along the tangent, continuing the direction of the last step
    double direction = 1.0;
    if (constraint.previous_increment.size() > 0) {
      const double along = passes_.translation_dot(constraint.previous_increment, a) + constraint.previous_load_increment * P2;
      direction = along < 0.0 ? -1.0 : 1.0;
    }
    return {direction * constraint.arc_length / std::sqrt(qa)};
  }
  passes_.free_displacements(state, increment_);
  increment_ -= start_;
  const double dl = state.load_factor - start_load_factor_;
  trial_ = increment_ + b;  // the increment after a correction with δλ = 0
  const ArcLengthQuadratic q{qa, 2.0 * (passes_.translation_dot(trial_, a) + dl * P2),
                             passes_.translation_dot(trial_, trial_) + dl * dl * P2 - s2};
  const std::optional<double> root = least_turning_root(q, passes_.translation_dot(increment_, trial_),
                                                        passes_.translation_dot(increment_, a), dl, P2);
  if (!root) return {0.0, StepFailure::Reason::arc_length_no_root};
  return {*root};
}

}  // namespace tsm::solver
