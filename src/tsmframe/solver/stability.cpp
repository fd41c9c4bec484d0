#include "tsmframe/solver/stability.hpp"

#include <algorithm>
#include <cmath>

namespace tsm::solver {
namespace {

constexpr int bisection_rounds = 30;          // a bifurcation's load factor: at most this many halvings …
constexpr double bisection_tolerance = 1e-6;  // … of its bracket, down to this fraction of λ

}  // namespace

/// The newest converged step and the one before it (null where there is none).
std::pair<StepRecord*, StepRecord*> newest_converged_two(std::vector<StepRecord>& steps) {
  StepRecord* found[2] = {nullptr, nullptr};
  int count = 0;
  for (auto s = steps.rbegin(); s != steps.rend() && count < 2; ++s)
    if (s->converged) found[count++] = &*s;
  return {found[0], found[1]};
}

bool inertia_tells_stability(const std::vector<contact::ContactState>& contacts) {
  return std::none_of(contacts.begin(), contacts.end(), [](const contact::ContactState& c) { return c.active; });
}

bool turned_unstable(const StepRecord* newest, const StepRecord* previous, const RunResult& result) {
  if (!newest || !previous || newest->negative_eigenvalues <= 0 || previous->negative_eigenvalues != 0) return false;
  return result.critical_points.empty() || result.critical_points.back().step != newest->step;
}

void locate_bifurcation(const StepRecord& newest, const StepRecord& previous, const State& from, NewtonSolver& newton,
                        TsmProblem& problem, RunResult& result) {
  double stable = previous.load_factor, unstable = newest.load_factor;
  bool rounded = false;  // some equilibrium's count was lost in round-off
  // Solves the equilibrium at λ = `at` and moves the bracket's end its inertia tells; false
  // where it tells nothing (no convergence, or round-off).
  const auto settle = [&](double at) {
    State trial = from;
    newton.reset(trial);
    PathConstraint constraint;
    constraint.load_increment = at - trial.load_factor;
    if (newton.step(constraint, trial).status != Status::converged) return false;
    const Factorisation f = problem.negative_eigenvalues(trial, true);
    rounded = rounded || f.rounded.has_value();
    if (f.negative_pivots < 0) return false;
    (f.negative_pivots > 0 ? unstable : stable) = at;
    return true;
  };
  const auto narrow = [&] {
    return std::abs(unstable - stable) <= bisection_tolerance * std::max(std::abs(stable), std::abs(unstable));
  };
  for (int round = 0; round < bisection_rounds && !narrow(); ++round) {
    if (settle(0.5 * (stable + unstable))) continue;
    if (!rounded) break;
    // Round-off hides the count near the critical point: the quarter points may lie outside
    // that band and still narrow the bracket.
    const bool nearer_stable = settle(0.75 * stable + 0.25 * unstable);
    if (!settle(0.25 * stable + 0.75 * unstable) && !nearer_stable) break;
  }
  result.critical_points.push_back({newest.step, 0.5 * (stable + unstable), stable, unstable, rounded && !narrow()});
}

void close_stability(RunResult& result, State& state, bool evaluated, bool load_control, NewtonSolver& newton,
                     TsmProblem& problem) {
  const auto [newest, previous] = newest_converged_two(result.steps);
  if (newest && newest->negative_eigenvalues < 0 && !newest->neutral && inertia_tells_stability(state.contacts)) {
    const Factorisation f = problem.negative_eigenvalues(state, evaluated);
    newest->negative_eigenvalues = f.negative_pivots;
    if (f.rounded) result.rounded_steps.push_back({newest->step, *f.rounded});
  }
  if (load_control && turned_unstable(newest, previous, result))  // the last step's, as the others'
    locate_bifurcation(*newest, *previous, state, newton, problem, result);
}

}  // namespace tsm::solver
