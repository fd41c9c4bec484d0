#pragma once
// When a Newton step has converged, and when it has failed for good (README "Convergence,
// precisely"): the force criterion on the relative residual, the round-off criteria (corrections
// at the rounding level of the displacements; a residual at the rounding floor of the internal
// forces), loads too small to resolve against that floor, and divergence (a blow-up of the
// residual against the step's force level, or displacements running away).

#include <array>
#include <cmath>

#include "tsmframe/assembly/global_system.hpp"
#include "tsmframe/solver/criterion.hpp"
#include "tsmframe/solver/problem.hpp"
#include "tsmframe/solver/state.hpp"
#include "tsmframe/solver/unbalanced_force.hpp"

namespace tsm::solver {

/// One iterate as the convergence test sees it.
struct IterateFacts {
  double relative = 0.0;                ///< its relative residual
  double previous = 0.0;                ///< the iterate before's
  ResidualPass residual;                ///< its unbalanced force's norms and scale
  std::array<double, 2> correction{};   ///< the correction's largest entries: translation, rotation
  std::array<double, 2> largest{};      ///< the largest displacements after it: translation, rotation
  bool contacts_changed = false;        ///< its evaluation changed the contact set
};

/// What the test made of an iterate.
struct Verdict {
  Criterion criterion = Criterion::none;
  /// The residual stays at the rounding level of the internal forces far from the tolerance:
  /// the loads are too small to be resolved against that rounding (floor: the facts).
  bool loads_unresolvable = false;
  assembly::RoundingFloor floor;
};

/// The test over the iterates of one step.
class ConvergenceTest {
 public:
  ConvergenceTest(const Problem& problem, double tolerance) : problem_(problem), tolerance_(tolerance) {}

  /// A step starts: the test's memory of earlier iterates is cleared.
  void begin_step();
  /// The step's force level: the scale at its target λ, at least the out-of-balance force that
  /// drives it (`drive`, per kind). Returns iterate 0's relative residual (the drive's).
  double set_step_scale(ResidualScale scale, const std::array<double, 2>& drive);
  /// A new contact brings its own force level into the step.
  void widen_step_scale(const ResidualScale& scale);
  Verdict judge(const IterateFacts& iterate, const State& state);
  /// Divergence: the residual 1e12 × the step's force level, or displacements beyond 1e6 × the
  /// model's size (where the chords would no longer be resolved) at load factor λ.
  bool diverged(const IterateFacts& iterate, double load_factor) const;

 private:
  /// Whether the structure carries no force above rounding: both kinds' scales within the floor
  /// ratio × the plain elements' rounding floor (contacts left out: a stiff contact's floor can
  /// dwarf the force it carries).
  bool carries_nothing(const ResidualScale& scale, const State& state) const;

  const Problem& problem_;
  double tolerance_;
  ResidualScale step_scale_;
  bool resolution_checked_ = false;  ///< a stagnating iterate far from the tolerance was held against the floor
  double lowest_ = INFINITY;  ///< the lowest relative residual of the step that halved the one before it
  int since_lowest_ = 0;      ///< iterates since then
};

/// ‖R‖ per kind within a small multiple of the rounding floor of the internal forces.
bool within_floor(const std::array<double, 2>& residual_norms, const assembly::RoundingFloor& floor);

/// How far an iterate may move with every element's chord still resolved to a fraction of its
/// length: the shortest l0 over that fraction of ε (0 without elements).
double resolvable_move(double shortest_element);

}  // namespace tsm::solver
