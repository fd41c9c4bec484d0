#pragma once
// Newton–Raphson on the unbalanced force R(D, λ) = λ F_ref − F(D) for one step of a path
// (FORMULATION §4). The first solve of a step is the tangent predictor, which also carries the
// prescribed displacements in (D_free += −K_ff⁻¹ K_fp ΔD_p); later solves correct with the
// exact (strict-compatibility) residual.

#include <array>
#include <string>
#include <vector>

#include "tsmframe/assembly/global_system.hpp"
#include "tsmframe/solver/linear_solver.hpp"
#include "tsmframe/solver/state.hpp"
#include "tsmframe/solver/status.hpp"
#include "tsmframe/solver/step_record.hpp"

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

struct NewtonSettings {
  double tolerance = 1e-8;
  int max_iterations = 50;
};

struct NewtonOutcome {
  Status status = Status::converged;   ///< converged, or how it failed
  std::string message;
  int iterations = 0;
  std::vector<double> residual_norms;  ///< relative, iterate 0 first
  std::string criterion;               ///< "force" or "round-off"
  std::vector<std::vector<ContactPoint>> contact_iterates;  ///< per iterate, iterate 0 first
  /// Negative eigenvalues of the tangent (its symmetric part) at the step's first factorisation
  /// (−1: unknown) and the most at any later one in the step.
  int start_negative_pivots = -1, most_negative_pivots = 0;
  /// Bergan's current stiffness at the step's start: |Δλ| / ‖ΔD‖ of the first iterate (the
  /// tangent's own response to the load, translations only); 0 where the first iterate moved
  /// nothing or changed no λ.
  double start_stiffness = 0.0;
  /// Accepted on round-off because the structure carries next to nothing (its forces at rounding
  /// level: a contact let go, or nothing loads it): its relative residual is noise.
  bool carried_nothing = false;
  /// Contacts released in the step because their point left a beam's free end, and stayed so:
  /// (contact index, the element whose end it left).
  std::vector<std::pair<int, int>> slid_off;
  /// Failed because the loads are too small to resolve against the rounding in the model's
  /// forces: a smaller step cannot help.
  bool loads_unresolvable = false;
  /// The step failed at its first iterate for a reason its size does not change (the controlled
  /// dof does not move under the load at the step's start): cutting it back cannot help.
  bool size_independent = false;
};

/// Force and moment scales of the convergence test (unit-consistent: each kind on its own).
struct ResidualScale {
  double force = 0.0;
  double moment = 0.0;
};

class NewtonSolver {
 public:
  /// `contacts` (may be null: no contacts) runs the contact life cycle after every evaluation.
  NewtonSolver(assembly::GlobalSystem& system, const NewtonSettings& settings,
               const contact::ContactTracker* contacts = nullptr);

  /// Makes `state` the start of the next step: evaluates the structure there (tangent included).
  void reset(State& state);
  /// One step from the state given to reset() or left by the last converged step. On failure
  /// `state` is left at the failed iterate: call reset() with the saved state before retrying.
  NewtonOutcome step(const PathConstraint& constraint, State& state);

  /// Negative eigenvalues of the tangent at `state` (its inertia, by one LDLᵀ factorisation): 0
  /// where that equilibrium is stable, n > 0 where it is not; −1 if the tangent does not
  /// factorise. `evaluated`: the last evaluation was at `state` (a step converged there and
  /// nothing was factorised since), else it is evaluated again. Uses up the tangent: a step
  /// after it must start with reset().
  int negative_eigenvalues(State& state, bool evaluated);
  /// The contacts of `state` as reported (element, α, force).
  std::vector<ContactPoint> contact_points(const State& state) const;
  /// Element forces (N, M_i, M_j) at `state` (a converged state: its chord rotations are its
  /// evaluation's).
  Eigen::VectorXd element_forces(const State& state) const;
  /// Support reactions of the last evaluation: F − λ F_ref on constrained dofs, 0 elsewhere.
  Eigen::VectorXd reactions(double load_factor) const;

 private:
  /// Evaluates at `state` and settles its contacts (detect, release, hand over; re-evaluating
  /// after each change). Returns whether the contact set changed. `contacts_only`: the state is
  /// the last evaluation's, only its contacts changed (what they touch is evaluated again).
  bool evaluate(State& state, bool contacts_only = false);
  /// The contact elements standing in for beam elements at `state` (none without contacts).
  std::vector<contact::ActiveContact> active_contacts(const State& state) const;
  /// At a converged iterate: releases contacts that pull and re-evaluates. Returns whether any was.
  bool release_pulling_contacts(State& state);
  /// At a converged iterate where contacts pull: the contacts that pull once those have let go,
  /// and so on (a linearised active-set iteration on the tangent here, see newton.cpp); empty
  /// where it does not apply. Sets `overwrote_tangent` when it factorised the tangent in place.
  std::vector<int> look_ahead_releases(State& state, bool& overwrote_tangent);
  /// What one pass over the unbalanced force yields.
  struct ResidualPass {
    std::array<double, 2> norms{};  ///< 2-norms of R per kind: forces, moments
    ResidualScale scale;             ///< the scale at this λ
    bool finite = true;              ///< R and the internal forces (constrained dofs too) are finite
  };
  /// R = λ F_ref − F(D) over the free equations into residual_, with its norms and the scale,
  /// in one pass (fixed chunks, bit-identical for any number of threads).
  ResidualPass update_residual(double load_factor);
  /// The scale alone at any λ (the state's internal forces).
  ResidualScale scale(double load_factor) const;
  /// The scale from squared sums per kind over the free equations (applied loads, internal
  /// forces); adds the constrained dofs' reactions and internal forces.
  ResidualScale scale_from(std::array<double, 2> load, std::array<double, 2> internal, double load_factor) const;
  std::array<double, 2> kind_norms(const Eigen::VectorXd& free_vector) const;  // 2-norms: forces, moments
  /// The reference load F_ref at the last evaluation's state: the model's, plus its follower
  /// loads on the current geometry where it has any.
  const Eigen::VectorXd& reference_load() const {
    return eval_.reference_load.size() > 0 ? eval_.reference_load : system_.model().reference_load;
  }
  /// F_dir = F_ref − K_fp D_p,ref over the free equations (dR/dλ), into `out`.
  void load_direction(Eigen::VectorXd& out) const;
  /// K_ff⁻¹ F_dir into along_load_ and K_ff⁻¹ R into along_residual_ (arc-length and
  /// displacement control: δD = δD_R + δλ δD_F).
  void solve_along_load_and_residual();
  /// v += Δλ F_dir, without forming F_dir.
  void add_load_direction(double dlambda, Eigen::VectorXd& v) const;
  double relative_norm(const std::array<double, 2>& norms, const ResidualScale& scale) const;
  /// What adding a correction found, per kind (translations, rotations): its largest entries
  /// (NaN if any entry is not finite) and the largest free displacements after it.
  struct Correction {
    std::array<double, 2> size{};
    std::array<double, 2> largest_free{};
  };
  /// Adds the correction to the free dofs, in one pass with its maxima.
  Correction apply_correction(const Eigen::VectorXd& correction, State& state) const;
  /// Largest |translation| and |rotation| over all dofs of `state`, given those over the free
  /// dofs (apply_correction): the constrained ones are added here.
  std::array<double, 2> largest_displacements(const State& state, std::array<double, 2> free) const;
  /// ‖R‖ per kind within a small multiple of the rounding floor of the internal forces.
  bool within_floor(const std::array<double, 2>& residual_norms, const State& state) const;
  static bool within_floor(const std::array<double, 2>& residual_norms, const assembly::RoundingFloor& floor);
  /// Whether the structure carries no force above rounding: both kinds' scales within the floor
  /// ratio × the plain elements' rounding floor (contacts left out: a stiff contact's floor can
  /// dwarf the force it carries).
  bool carries_nothing(const ResidualScale& scale, const State& state) const;
  /// The active contact (index) on `element`, −1 if none.
  int contact_on(const State& state, int element) const;
  /// step() without the note a failure gets when the structure lost the contacts holding it.
  NewtonOutcome iterate_step(const PathConstraint& constraint, State& state);
  /// Translational part of dot products for the arc-length constraint.
  double arc_dot(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const;
  void free_displacements(const State& state, Eigen::VectorXd& out) const;

  assembly::GlobalSystem& system_;
  NewtonSettings settings_;
  const contact::ContactTracker* contacts_ = nullptr;
  /// Contacts (model order) resting on the structure as drawn that it needs: without them
  /// (model/mechanism) it is a mechanism. Empty otherwise.
  std::vector<int> holding_contacts_;
  int switches_ = 0;   ///< contact activations + releases in the current step
  int reversals_ = 0;  ///< contact hand-overs back the way the point came, in the current step
  LinearSolver solver_;
  assembly::Evaluation eval_;
  // Workspace of step(), kept between iterations and steps: no allocation per iteration. Under
  // load control only residual_ is used (the correction overwrites it).
  Eigen::VectorXd residual_, correction_, along_load_, along_residual_, start_, increment_, trial_, drive_;
  Eigen::VectorXd kept_rhs_;  ///< a right-hand side kept for a second factorisation (with the sliding terms)
  std::vector<unsigned char> is_moment_;  ///< per free equation: 1 for a rotation dof (cheaper than dof % 3 in the hot passes)
  std::vector<int> constrained_dofs_;
  double prescribed_squared_ = 0.0;  ///< ‖D_p,ref‖² over prescribed translations
  /// How far an iterate may move with every element's chord still resolved to chord_resolution
  /// (newton.cpp): the shortest l0 over that fraction of ε; 0 without elements.
  double resolvable_move_ = 0.0;
  int analysed_pattern_ = -1;        ///< pattern version the linear solver has analysed
};

}  // namespace tsm::solver
