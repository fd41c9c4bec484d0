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
  for (int round = 0; round < bisection_rounds; ++round) {
    if (std::abs(unstable - stable) <= bisection_tolerance * std::max(std::abs(stable), std::abs(unstable))) break;
    const double middle = 0.5 * (stable + unstable);
    State trial = from;
    newton.reset(trial);
    PathConstraint constraint;
    constraint.load_increment = middle - trial.load_factor;
    if (newton.step(constraint, trial).status != Status::converged) break;
    const int negatives = problem.negative_eigenvalues(trial, true);
    if (negatives < 0) break;
    (negatives > 0 ? unstable : stable) = middle;
  }
  result.critical_points.push_back({newest.step, 0.5 * (stable + unstable), stable, unstable});
}

void close_stability(RunResult& result, State& state, bool evaluated, bool load_control, NewtonSolver& newton,
                     TsmProblem& problem) {
  const auto [newest, previous] = newest_converged_two(result.steps);
  if (newest && newest->negative_eigenvalues < 0 && !newest->neutral && inertia_tells_stability(state.contacts))
    newest->negative_eigenvalues = problem.negative_eigenvalues(state, evaluated);
  if (load_control && turned_unstable(newest, previous, result))  // the last step's, as the others'
    locate_bifurcation(*newest, *previous, state, newton, problem, result);
}

}  // namespace tsm::solver
