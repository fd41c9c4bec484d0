#pragma once
// How the load factor moves within a Newton step (FORMULATION §4): fixed after the predictor
// (load control), chosen every iterate so that one free dof reaches its target (displacement
// control), or so that the step's increment keeps its arc length (Crisfield's arc-length
// control). Every correction is δD = δD_R + δλ δD_F, with δD_F = K⁻¹ F_dir the response to
// the load (F_dir = dR/dλ) and δD_R = K⁻¹ R the response to the unbalanced force.

#include <Eigen/Core>
#include <optional>

#include "tsmframe/solver/failure.hpp"
#include "tsmframe/solver/state.hpp"
#include "tsmframe/solver/unbalanced_force.hpp"

namespace tsm::solver {

/// How the load factor moves within a step.
struct PathConstraint {
  enum class Kind {
    load_increment,       ///< λ += increment in the predictor, then fixed
    displacement_target,  ///< λ chosen every iterate so that one free dof equals target
    arc_length,           ///< the step's increment (ΔD, Δλ) has length arc_length (Crisfield)
  } kind = Kind::load_increment;
  double load_increment = 0.0;
  int equation = -1;  ///< free equation of the controlled dof
  double target = 0.0;
  /// Arc length Δs: ‖ΔD_t‖² + Δλ² ‖D_p,ref‖² = Δs², ΔD_t the translations of the free dofs and
  /// D_p,ref the prescribed translations (cylindrical in the free dofs, spherical in the
  /// prescribed ones, which move with λ).
  double arc_length = 0.0;
  /// The last converged step's increment (free equations) and Δλ, for the direction of the
  /// predictor; empty at the start of the path (λ then rises).
  Eigen::VectorXd previous_increment;
  double previous_load_increment = 0.0;
};

/// δλ of an iterate, or why there is none.
struct PathCorrection {
  double dlambda = 0.0;
  StepFailure::Reason failure = StepFailure::Reason::none;
};

/// The arc-length constraint on the next correction, a δλ² + b δλ + c = 0.
struct ArcLengthQuadratic {
  double a = 0.0, b = 0.0, c = 0.0;
};
/// Of its two roots, the one whose new increment turns least from the step's increment so far
/// (no doubling back): the increment's dot product with the new one is
/// along_trial + δλ · along_load + Δλ (Δλ + δλ) P², largest. None where it has no real root.
std::optional<double> least_turning_root(const ArcLengthQuadratic& q, double along_trial, double along_load,
                                         double load_increment, double prescribed_squared);

/// The corrections' δλ under displacement and arc-length control over one problem's equations.
class PathControl {
 public:
  explicit PathControl(const UnbalancedForce& passes) : passes_(passes) {}

  /// A step starts at `state` (arc-length control remembers where).
  void begin_step(const PathConstraint& constraint, const State& state);
  /// δλ of iterate `iteration` from a = K⁻¹ F_dir and b = K⁻¹ R (not under load control).
  PathCorrection correction(const PathConstraint& constraint, int iteration, const Eigen::VectorXd& a,
                            const Eigen::VectorXd& b, const State& state);

 private:
  PathCorrection arc_length(const PathConstraint& constraint, int iteration, const Eigen::VectorXd& a,
                            const Eigen::VectorXd& b, const State& state);

  const UnbalancedForce& passes_;
  Eigen::VectorXd start_, increment_, trial_;  // workspace, kept between steps
  double start_load_factor_ = 0.0;
};

}  // namespace tsm::solver
