#pragma once
// The Newton iteration's passes over the free equations: the unbalanced force R = λ F_ref − F
// with its norms per kind and the force scale in one pass, a correction added to the state with
// its maxima in one pass, and the vectors of path control (dR/dλ). Each runs in fixed chunks
// (util/chunked_reduce): bit-identical for any number of threads.

#include <Eigen/Core>
#include <array>

#include "tsmframe/solver/problem.hpp"
#include "tsmframe/solver/state.hpp"

namespace tsm::solver {

/// Force and moment scales of the convergence test (unit-consistent: each kind on its own).
struct ResidualScale {
  double force = 0.0;
  double moment = 0.0;
};

/// What one pass over the unbalanced force yields.
struct ResidualPass {
  std::array<double, 2> norms{};  ///< 2-norms of R per kind: forces, moments
  ResidualScale scale;             ///< the scale at this λ
  bool finite = true;              ///< R and the internal forces (constrained dofs too) are finite
};

/// What adding a correction found, per kind (translations, rotations): its largest entries
/// (NaN if any entry is not finite) and the largest free displacements after it.
struct AppliedCorrection {
  std::array<double, 2> size{};
  std::array<double, 2> largest_free{};
};

/// The passes over one problem's equations and its last evaluation's vectors.
class UnbalancedForce {
 public:
  explicit UnbalancedForce(const Problem& problem) : problem_(problem), equations_(problem.equations()) {}

  const Equations& equations() const { return equations_; }

  /// R = λ F_ref − F over the free equations into `residual`, with its norms and the scale.
  ResidualPass update(double load_factor, Eigen::VectorXd& residual) const;
  /// The scale alone at any λ (the state's internal forces).
  ResidualScale scale(double load_factor) const;
  /// 2-norms per kind (forces, moments) of a vector over the free equations.
  std::array<double, 2> kind_norms(const Eigen::VectorXd& free_vector) const;
  /// F_dir = F_ref − K_fp D_p,ref over the free equations (dR/dλ), into `out`.
  void load_direction(Eigen::VectorXd& out) const;
  /// v += Δλ F_dir, without forming F_dir.
  void add_load_direction(double dlambda, Eigen::VectorXd& v) const;
  /// Adds the correction to the state's free dofs, in one pass with its maxima.
  AppliedCorrection apply(const Eigen::VectorXd& correction, State& state) const;
  /// Largest |translation| and |rotation| over all dofs of `state`, given those over the free
  /// dofs (apply): the constrained ones are added here.
  std::array<double, 2> largest_displacements(const State& state, std::array<double, 2> free) const;
  /// The translations' part of a dot product of two vectors over the free equations.
  double translation_dot(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const;
  /// The state's displacements of the free equations, into `out`.
  void free_displacements(const State& state, Eigen::VectorXd& out) const;

 private:
  /// The scale from squared sums per kind over the free equations (applied loads, internal
  /// forces); adds the constrained dofs' reactions and internal forces.
  ResidualScale scale_from(std::array<double, 2> load, std::array<double, 2> internal, double load_factor) const;
  /// The dead load's entries (null: none), all dofs.
  const double* dead_load() const;

  const Problem& problem_;
  const Equations& equations_;
};

/// ‖R‖ relative to the scale, the larger of the two kinds' (0 / 0 = 0, x / 0 = ∞).
double relative_norm(const std::array<double, 2>& norms, const ResidualScale& scale);

}  // namespace tsm::solver
