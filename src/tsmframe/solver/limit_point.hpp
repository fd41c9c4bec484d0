#pragma once
// A limit point of an arc-length path located, not read off the nearest step: λ's extremum
// between the converged steps around it, by successive parabolic interpolation on λ(u) — u a dof
// that moves one way through the extremum, each λ(u) an equilibrium solved under displacement
// control from the step nearest the peak.

#include <Eigen/Core>
#include <array>
#include <optional>

#include "tsmframe/assembly/dof_map.hpp"
#include "tsmframe/solver/newton.hpp"
#include "tsmframe/solver/state.hpp"
#include "tsmframe/solver/step_record.hpp"

namespace tsm::solver {

/// The search ends where a trial's λ is within this fraction of the best found before it (the
/// parabola's vertex on the flat top): below the equilibria's own accuracy (the Newton tolerance, 1e-8 by
/// default) it would only follow their residuals.
inline constexpr double limit_point_tolerance = 1e-9;

/// The free equation that moves most, and one way, over both increments (`before`: into the
/// peak's step, `after`: out of it), each equation's movement times its `scale` (0: not a
/// candidate); −1 where none moves one way.
int monotone_equation(const Eigen::VectorXd& before, const Eigen::VectorXd& after, const Eigen::VectorXd& scale);

/// Three equilibria on the path around a strict extremum of λ: the controlled equation's values
/// `u` (ascending or descending) and their λ, the middle one the extreme step's.
struct LimitBracket {
  int step = 0;                 ///< the extreme step
  bool maximum = true;
  int equation = -1;
  std::array<double, 3> u{}, load_factor{};
};

/// The extremum of λ(u) within the bracket, each λ(u) solved from `start` (the extreme step's
/// state) by `newton` under displacement control; none where an equilibrium there fails. Leaves
/// `newton` evaluated at a trial state: the caller resets it.
std::optional<RefinedLimit> refine_limit_point(const LimitBracket& bracket, const State& start,
                                               const assembly::DofMap& dofs, NewtonSolver& newton);

}  // namespace tsm::solver
