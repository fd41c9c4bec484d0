#pragma once
// What the Newton iteration sees of the structure (cf. polysolve's Problem): its equations, an
// evaluation at a state (internal forces, reference load, tangent), the linear solve with that
// tangent, and hooks where the structure's own passes run — after every iterate, at a converged
// iterate (contacts that pull let go, a node through a beam touches again), when a step is
// accepted. Newton itself knows nothing of elements or contacts (tsm_problem.hpp implements it).

#include <Eigen/Core>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "tsmframe/assembly/global_system.hpp"
#include "tsmframe/solver/failure.hpp"
#include "tsmframe/solver/state.hpp"
#include "tsmframe/solver/step_record.hpp"

namespace tsm::solver {

/// The unknowns: the free equations in the tangent's order and the dofs held (fixed or
/// prescribed). Vectors "over the free equations" have free_count() entries; state vectors one
/// per dof.
struct Equations {
  std::span<const int> free_dofs;         ///< the dof of each free equation (the problem's storage)
  std::vector<unsigned char> is_moment;   ///< per free equation: 1 for a rotation dof (cheaper than dof % 3 in the hot passes)
  std::vector<int> constrained_dofs;      ///< the dofs held, ascending
  double size = 1.0;                ///< the model's size (its bounding box's diagonal)
  double prescribed_size = 0.0;     ///< ‖D_p,ref‖∞: the largest prescribed displacement at λ = 1
  double prescribed_squared = 0.0;  ///< ‖D_p,ref‖² over the prescribed translations
  /// How far an iterate may move with every element's chord still resolved (convergence.hpp);
  /// 0 without elements.
  double resolvable_move = 0.0;
  int free_count() const { return static_cast<int>(free_dofs.size()); }
};

/// A factorisation of the tangent: whether it succeeded and the negative eigenvalues of its
/// symmetric part (−1: unknown — the tangent not symmetric, or round-off leaves the count in
/// doubt, `rounded` saying where).
struct Factorisation {
  bool ok = false;
  int negative_pivots = -1;
  std::optional<RoundedInertia> rounded;
};

/// How far Newton judges an iterate to be from the solution, by the relative residual before
/// the correction that reached it (newton.cpp: far from 10⁻² up). Far off, Newton leaves the
/// tangent's optional terms out, and the structure may evaluate a simpler model — one whose
/// iterates are never accepted as converged (at_convergence evaluates them again, near).
enum class Proximity { near, far };

/// What the structure's passes at a converged iterate decided.
struct Settlement {
  enum class Kind {
    settled,     ///< the iterate is an acceptable equilibrium: the step converges here
    iterate_on,  ///< the contacts changed (a release, a node touching again): Newton goes on
    failed,      ///< no iterate can make it acceptable (failure says why)
  } kind = Kind::settled;
  /// The state was evaluated again (its residual and contacts are new).
  bool evaluated_again = false;
  StepFailure failure;
};

class Problem {
 public:
  virtual ~Problem() = default;

  virtual const Equations& equations() const = 0;
  /// Whether the structure has contacts (whose points Newton logs per iterate).
  virtual bool has_contacts() const = 0;

  // --- evaluation
  /// Evaluates the structure at `state` (its prescribed dofs set from λ first) and runs the
  /// structure's passes at this iterate (contacts detected, handed over, released). Returns
  /// whether those changed the state beyond its displacements (the contact set). `proximity`:
  /// far, the contacts may push along their chords' normals (tsm_problem.cpp).
  virtual bool evaluate(State& state, Proximity proximity) = 0;
  bool evaluate(State& state) { return evaluate(state, Proximity::near); }
  /// F at the last evaluation, all dofs.
  virtual const Eigen::VectorXd& internal_force() const = 0;
  /// F_ref at the last evaluation (follower loads on the current geometry), all dofs.
  virtual const Eigen::VectorXd& reference_load() const = 0;
  /// The load earlier stages left, held whatever λ, at the last evaluation, all dofs (empty: none).
  virtual const Eigen::VectorXd& dead_load() const = 0;
  /// K_fp D_p,ref over the free equations at the last evaluation (empty: nothing prescribed).
  virtual const Eigen::VectorXd& prescribed_coupling() const = 0;
  /// The rounding floor of the internal forces at `state` (a pass of its own), the active
  /// contacts' share included or not.
  virtual assembly::RoundingFloor rounding_floor(const State& state, bool with_contacts) const = 0;

  // --- the tangent
  /// Whether the tangent has terms Newton may leave out far from the solution (the contacts'
  /// sliding terms).
  virtual bool has_optional_terms() const = 0;
  /// Factorises the tangent of the last evaluation, at `state`, with or without the optional
  /// terms (without them where asked, then with them if the rest alone is singular); with `rhs`,
  /// solves for it in place. `stability`: its inertia will be read as the stability of the
  /// equilibrium at `state` (a step's first iterate): guarded against round-off.
  virtual Factorisation factorize(const State& state, bool with_optional_terms, Eigen::VectorXd* rhs, bool stability) = 0;
  /// Solves with the last factorisation, in place.
  virtual void solve_in_place(Eigen::VectorXd& x) const = 0;

  /// The fraction (0, 1] of Newton's correction (over the free equations) to apply from `state`:
  /// less where the structure's own passes ask it (contacts landing deep, landing.hpp).
  virtual double step_fraction(const State& state, const Eigen::VectorXd& correction) = 0;

  // --- hooks
  /// A step starts from `state` (evaluated): its per-step bookkeeping restarts.
  virtual void begin_step(const State& state) = 0;
  /// After an iterate's evaluation: a failure the structure's passes met (contacts cycling).
  virtual std::optional<StepFailure> after_iterate(const State& state) const = 0;
  /// At an iterate that meets the convergence criterion.
  virtual Settlement at_convergence(State& state) = 0;
  /// The step converged at `state`; returns the contacts that let go in it because their point
  /// left a beam's free end, and stayed so: (contact index, the element whose end it left).
  virtual std::vector<std::pair<int, int>> accept(State& state) = 0;
  /// A failed step's facts that only the structure knows (member releases, contacts, what held
  /// it, the motion a mechanism leaves free), added to `failure`. May use up the tangent.
  virtual void explain(const State& state, StepFailure& failure) = 0;
  /// The contacts of `state` as reported (element, α, force).
  virtual std::vector<ContactPoint> contact_points(const State& state) const = 0;
};

}  // namespace tsm::solver
