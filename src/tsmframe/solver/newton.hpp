#pragma once
// Newton–Raphson on the unbalanced force R(D, λ) = λ F_ref − F(D) for one step of a path
// (FORMULATION §4). The first solve of a step is the tangent predictor, which also carries the
// prescribed displacements in (D_free += −K_ff⁻¹ K_fp ΔD_p); later solves correct with the
// exact (strict-compatibility) residual. Newton sees only a Problem (problem.hpp); how λ moves
// is path_control's, when the step has converged or failed is convergence's.

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "tsmframe/solver/convergence.hpp"
#include "tsmframe/solver/failure.hpp"
#include "tsmframe/solver/path_control.hpp"
#include "tsmframe/solver/problem.hpp"
#include "tsmframe/solver/state.hpp"
#include "tsmframe/solver/status.hpp"
#include "tsmframe/solver/step_record.hpp"
#include "tsmframe/solver/unbalanced_force.hpp"

namespace tsm::solver {

struct NewtonSettings {
  double tolerance = 1e-8;
  int max_iterations = 50;
};

struct NewtonOutcome {
  Status status = Status::converged;   ///< converged, or how it failed
  StepFailure failure;                 ///< why it failed (reason none when converged)
  int iterations = 0;
  std::vector<double> residual_norms;  ///< relative, iterate 0 first
  Criterion criterion = Criterion::none;
  std::vector<std::vector<ContactPoint>> contact_iterates;  ///< per iterate, iterate 0 first
  /// Negative eigenvalues of the tangent (its symmetric part) at the step's first factorisation
  /// (−1: unknown) and the most at any later one in the step.
  int start_negative_pivots = -1, most_negative_pivots = 0;
  /// Where round-off left the first factorisation's inertia unknown.
  std::optional<RoundedInertia> start_rounded;
  /// Bergan's current stiffness at the step's start: |Δλ| / ‖ΔD‖ of the first iterate (the
  /// tangent's own response to the load, translations only); 0 where the first iterate moved
  /// nothing or changed no λ.
  double start_stiffness = 0.0;
  /// Contacts released in the step because their point left a beam's free end, and stayed so:
  /// (contact index, the element whose end it left).
  std::vector<std::pair<int, int>> slid_off;
};

class NewtonSolver {
 public:
  NewtonSolver(Problem& problem, const NewtonSettings& settings);

  /// Makes `state` the start of the next step: evaluates the structure there (tangent included).
  void reset(State& state) { problem_.evaluate(state); }
  /// One step from the state given to reset() or left by the last converged step. On failure
  /// `state` is left at the failed iterate: call reset() with the saved state before retrying.
  NewtonOutcome step(const PathConstraint& constraint, State& state);

 private:
  /// The iterate's correction into `correction` (δD) and δλ, from a factorisation of the tangent;
  /// failure: why there is none.
  PathCorrection solve(const PathConstraint& constraint, int iteration, const State& state, NewtonOutcome& out,
                       Eigen::VectorXd*& correction);
  /// Iterate 1: the step's force level (the scale at its target λ and the force that drives
  /// it), its start stiffness, and iterate 0's relative residual.
  void measure_start(const PathConstraint& constraint, double dlambda, const Eigen::VectorXd& correction,
                     const State& state, NewtonOutcome& out);
  NewtonOutcome iterate(const PathConstraint& constraint, State& state);
  /// Ends the step as failed at iteration `iteration`.
  static NewtonOutcome& fail(NewtonOutcome& out, StepFailure failure, int iteration);

  Problem& problem_;
  NewtonSettings settings_;
  UnbalancedForce passes_;
  PathControl path_;
  ConvergenceTest test_;
  ResidualPass pass_;       ///< the last pass over the unbalanced force
  std::array<double, 2> drive_norms_{};  ///< load control: the norms of iterate 0's drive (its right-hand side)
  bool been_near_ = false;  ///< the step has had an iterate near the solution: every later one is evaluated near
  // Workspace of step(), kept between iterations and steps: no allocation per iteration. Under
  // load control only residual_ is used (the correction overwrites it).
  Eigen::VectorXd residual_, correction_, along_load_, along_residual_, drive_;
};

}  // namespace tsm::solver
