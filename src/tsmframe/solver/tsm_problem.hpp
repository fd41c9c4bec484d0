#pragma once
// The Tangent Stiffness Method structure as Newton's problem: the global system (elements and
// contact elements) evaluated at a state, its tangent factorised by the linear solver (the
// contacts' sliding terms and the follower loads' skew terms beside it), and the contact life
// cycle run where Newton's hooks call it — detection, hand-over and release after every iterate,
// the release of pulling contacts (with its look-ahead) at a converged iterate, and the
// switching budget that ends a step whose contacts never settle.

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "tsmframe/assembly/global_system.hpp"
#include "tsmframe/contact/contact_set.hpp"
#include "tsmframe/solver/linear_solver.hpp"
#include "tsmframe/solver/problem.hpp"

namespace tsm::solver {

class TsmProblem final : public Problem {
 public:
  /// `contacts` (may be null: no contacts) runs the contact life cycle after every evaluation.
  TsmProblem(assembly::GlobalSystem& system, const contact::ContactSet* contacts = nullptr);

  const Equations& equations() const override { return equations_; }
  bool has_contacts() const override { return contacts_ != nullptr; }
  using Problem::evaluate;
  bool evaluate(State& state, Proximity proximity) override { return evaluate(state, proximity, false); }
  const Eigen::VectorXd& internal_force() const override { return eval_.internal_force; }
  const Eigen::VectorXd& reference_load() const override {
    return eval_.reference_load.size() > 0 ? eval_.reference_load : system_.model().reference_load;
  }
  const Eigen::VectorXd& dead_load() const override {
    return eval_.dead_load.size() > 0 ? eval_.dead_load : system_.model().dead_load;
  }
  const Eigen::VectorXd& prescribed_coupling() const override { return eval_.prescribed_coupling; }
  assembly::RoundingFloor rounding_floor(const State& state, bool with_contacts) const override;
  bool has_optional_terms() const override { return !system_.contact_rank_one().empty(); }
  Factorisation factorize(const State& state, bool with_optional_terms, Eigen::VectorXd* rhs, bool stability) override;
  void solve_in_place(Eigen::VectorXd& x) const override { solver_.solve_in_place(x); }
  double step_fraction(const State& state, const Eigen::VectorXd& correction) override;
  void begin_step(const State& state) override;
  std::optional<StepFailure> after_iterate(const State& state) const override;
  Settlement at_convergence(State& state) override;
  std::vector<std::pair<int, int>> accept(State& state) override;
  /// Takes the references of the contacts that have none at `state` (a run's first state, a
  /// restart's, contacts a stage brings back; contact_set's restore), and where they were taken.
  void take_contact_references(State& state) const;
  void explain(const State& state, StepFailure& failure) override;
  /// The free motion the tangent at the unloaded state (`state`'s, its displacements and λ zero) leaves, within `within_shifts` shifts of
  /// zero (free_mode.hpp), named in `failure` (Reason::mechanism); whether there is one.
  bool name_unloaded_mechanism(const State& state, StepFailure& failure, double within_shifts);
  std::vector<ContactPoint> contact_points(const State& state) const override;

  const Model& model() const { return system_.model(); }
  /// The tangent at `state` factorised once for its inertia: negative_pivots 0 where that
  /// equilibrium is stable, n > 0 where it is not; −1 if the tangent does not factorise, is not
  /// symmetric or round-off leaves the count in doubt (`rounded`). `evaluated`: the last
  /// evaluation was at `state` (a step converged there and nothing was factorised since), else it
  /// is evaluated again. Uses up the tangent: a step after it must start with an evaluation.
  Factorisation negative_eigenvalues(State& state, bool evaluated);
  /// Element forces (N, M_i, M_j) at `state` (a converged state: its chord rotations are its
  /// evaluation's).
  Eigen::VectorXd element_forces(const State& state) const;
  /// Support reactions of the last evaluation: F − λ F_ref on constrained dofs, 0 elsewhere,
  /// global (a skew roller's in x and y).
  Eigen::VectorXd reactions(double load_factor) const;
  /// The internal force at every dof of the last evaluation, global: at an equilibrium the loads,
  /// and at constrained dofs the reactions with them.
  Eigen::VectorXd global_internal_force() const;
  /// Whether the last evaluation's loads are conservative (no follower load's non-symmetric term).
  bool loads_conservative() const { return system_.follower_rank_one().empty(); }
  /// The state's displacements, global: the state holds a skew roller's node's translations in
  /// its frame (model/nodal_frames.hpp); elsewhere they are the state's own.
  const Eigen::VectorXd& physical(const State& state) const;
  /// Whether the state's displacements are not global (a skew roller turns a frame).
  bool turns_frames() const { return !system_.frames().empty(); }

 private:
  mutable Eigen::VectorXd physical_;  ///< physical()'s, where frames turn
  Eigen::VectorXd trial_;  ///< step_fraction()'s: the iterate a whole correction would reach
  bool from_unloaded_ = false;        ///< the step began at the unloaded state (begin_step)
  /// Evaluates at `state` and settles its contacts (detect, release, hand over; re-evaluating
  /// after each change). Returns whether the contact set changed, or the points' normals turned
  /// back from the chords' to the bent beams' (Problem::evaluate). `contacts_only`: the state is
  /// the last evaluation's, only its contacts changed (what they touch is evaluated again).
  bool evaluate(State& state, Proximity proximity, bool contacts_only);
  /// Whether an iterate `proximity` from the solution pushes along the chords' normals: far,
  /// with many points in touch along bent beams' normals (tsm_problem.cpp).
  bool far_along_chords(const State& state, Proximity proximity);
  /// After the landing cut an iterate short: the contacts started at it put back on the surface
  /// they landed on (contact::landing_move, state.displacements moved); whether any node moved.
  bool put_on_surface(State& state);
  /// The contact elements standing in for beam elements at `state` (none without contacts).
  std::vector<contact::ActiveContact> active_contacts(const State& state) const;
  /// Analyses the tangent's pattern again where a contact has joined new nodes.
  void analyse_pattern();
  /// At a converged iterate: releases contacts that pull and re-evaluates. Returns whether any was.
  bool release_pulling_contacts(State& state);
  /// At a converged iterate where contacts pull: the contacts that pull once those have let go,
  /// and so on (a linearised active-set iteration on the tangent here, see tsm_problem.cpp); empty
  /// where it does not apply. Sets `overwrote_tangent` when it factorised the tangent in place.
  std::vector<int> look_ahead_releases(State& state, bool& overwrote_tangent);
  /// The contacts switched on and off, or hopping back, more often in this step than a step may.
  bool switching_too_often() const { return switches_ > max_switches_; }
  /// The active contact (index) on `element`, −1 if none.
  int contact_on(const State& state, int element) const;

  assembly::GlobalSystem& system_;
  const contact::ContactSet* contacts_ = nullptr;
  Equations equations_;
  bool hinged_ = false;  ///< some member end is released (a singular tangent may be a mechanism among hinges)
  /// Contacts (model order) resting on the structure as drawn that it needs: without them
  /// (model/mechanism) it is a mechanism. Empty otherwise.
  std::vector<int> holding_contacts_;
  int switches_ = 0;   ///< contact activations + releases in the current step
  int reversals_ = 0;  ///< contact hand-overs back the way the point came, in the current step
  int max_switches_ = 0, max_reversals_ = 0;  ///< the current step's budget
  bool predictor_pending_ = false;  ///< the step's first evaluation (the predictor's iterate) is still to come
  bool landing_cut_ = false;        ///< the next evaluation's iterate is one the landing cut short (step_fraction)
  bool along_chords_ = false;       ///< the last evaluation's: every point pushes along its chord's normal (far, or a landing)
  bool bends_normals_ = false;      ///< some contact pushes along the bent beam's normal (ContactSet::bends_normals)
  std::vector<char> touching_before_;  ///< per contact: in touch before the landing iterate's update (put_on_surface)
  bool far_along_chords_ = false;   ///< this step's far iterates push along the chords (far_along_chords)
  LinearSolver solver_;
  /// The last factorisation's outcome and what it tells of the tangent's inertia (`symmetric`:
  /// no follower load's skew terms in it).
  Factorisation factorisation(bool ok, bool symmetric) const;
  assembly::Evaluation eval_;
  std::vector<contact::ActiveContact> active_;  ///< evaluate()'s contact elements, their storage reused pass by pass
  Eigen::VectorXd kept_rhs_;  ///< a right-hand side kept for a second factorisation (with the sliding terms)
  int analysed_pattern_ = -1;  ///< pattern version the linear solver has analysed
};

}  // namespace tsm::solver
