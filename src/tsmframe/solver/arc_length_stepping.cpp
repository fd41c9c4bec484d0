#include "tsmframe/solver/arc_length_stepping.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include "tsmframe/solver/diagnosis.hpp"
#include "tsmframe/solver/limit_point.hpp"
#include "tsmframe/solver/stability.hpp"
#include "tsmframe/solver/step_start.hpp"

namespace tsm::solver {
namespace {

// Step size: after a step of n iterations the next arc length is scaled by √(aim / n), at most
// doubled or halved, within [min_increment, max_increment]; a failed step is retried at half the
// arc length (cutback) until min_increment.
constexpr double aim_iterations = 6.0;

/// The quantity `until` watches at a state (docs/format.md `until`): λ or one dof. Only for a control
/// that has an `until` (Until::steps names no dof).
double watched(const Control& control, double load_factor, const Eigen::VectorXd& displacements) {
  if (control.until == Control::Until::load_factor) return load_factor;
  return displacements[dofs_per_node * control.until_node + control.until_dof];
}

class ArcLengthStepping {
 public:
  ArcLengthStepping(const Model& model, const assembly::DofMap& dofs, NewtonSolver& newton, TsmProblem& problem,
                    const StepObserver& observer, const StopRequest* stop)
      : model_(model), stop_(stop), settings_(model.analysis), control_(settings_.control), dofs_(dofs), newton_(newton),
        recorder_(model, problem, observer, result_), arc_(control_.initial_increment),
        watching_(control_.until != Control::Until::steps) {
    constraint_.kind = PathConstraint::Kind::arc_length;
  }

  RunResult run(State& state);

 private:
  /// A converged arc-length step: recorded, the next arc sized; returns whether it reached the
  /// `until` target (and landed on it exactly).
  bool converged(StepRecord record, const NewtonOutcome& outcome, State& state);
  /// Redoes the step that passed the `until` target from its start `landed` under load or
  /// displacement control, to land on the target exactly; keeps the arc-length step if that fails.
  void land(State landed, State& state);
  /// Whether the step from `start` to `state` passed (or reached) the `until` target.
  bool crosses_until(const Eigen::VectorXd& start, const State& state) const {
    const double before = watched(control_, saved_.load_factor(), start);
    const double after = watched(control_, state.load_factor, state.displacements);
    return (before - control_.until_value) * (after - control_.until_value) <= 0.0 && after != before;
  }
  /// Where the step just converged to `state` from `start` makes its start a strict extremum of λ:
  /// the bracket around it (not with contacts, whose references a trial equilibrium would move).
  std::optional<LimitBracket> limit_bracket(const Eigen::VectorXd& start, const State& state) const;
  /// Locates the limit point in `bracket` from `peak` (its step's state), then evaluates the
  /// structure at `state` again, where the path goes on.
  void locate(const LimitBracket& bracket, const State& peak, State& state);
  /// No arc reaches the path from the step's start (restored in `state`): one load-controlled
  /// step of the last Δλ across the jump. Returns whether it converged.
  bool jump_across(State& state);
  void give_up(StepRecord record, const NewtonOutcome& outcome);
  void stop_at_step_limit(const State& state);
  /// The run stops on request before the next attempt, `state` the newest converged step's.
  void interrupt(const State& state);

  const Model& model_;
  const StopRequest* stop_;
  const AnalysisSettings& settings_;
  const Control& control_;
  const assembly::DofMap& dofs_;
  NewtonSolver& newton_;
  RunResult result_;
  Recorder recorder_;
  PathConstraint constraint_;
  double arc_;
  int halvings_ = 0, converged_steps_ = 0;
  const bool watching_;
  // The converged step before the newest, for a limit point at the newest: its λ and number.
  double previous_start_lambda_ = std::nan("");
  int previous_step_ = 0;
  StepStart saved_;  // the start of the step being tried (reused: no allocation per step)
};

RunResult ArcLengthStepping::run(State& state) {
  recorder_.start_from(state);
  if (const ArcLengthMemory& memory = state.arc_length; memory.next_arc > 0.0) {  // a restart: go on as before
    if (watching_ && watched(control_, state.load_factor, state.displacements) == control_.until_value) {
      result_.status = Status::converged;  // it had landed on its `until`: the whole run ended there
      return std::move(result_);
    }
    arc_ = memory.next_arc;
    converged_steps_ = memory.converged_steps;
    constraint_.previous_increment.resize(memory.previous_increment.size() > 0 ? dofs_.free_count() : 0);  // none after a jump
    for (Eigen::Index eq = 0; eq < constraint_.previous_increment.size(); ++eq)
      constraint_.previous_increment[eq] = memory.previous_increment[dofs_.dof(static_cast<int>(eq))];
    constraint_.previous_load_increment = memory.previous_load_increment;
  }
  while (converged_steps_ < control_.max_steps) {
    if (stop_requested(stop_)) {
      interrupt(state);
      return std::move(result_);
    }
    saved_.take(state, recorder_.newest_displacements());
    constraint_.arc_length = arc_;
    const bool tells_stability = inertia_tells_stability(state.contacts);
    const NewtonOutcome outcome = newton_.step(constraint_, state);
    recorder_.started_from_newest(outcome, tells_stability);
    StepRecord record = recorder_.start(outcome, halvings_);
    record.arc_length = arc_;
    if (outcome.status == Status::converged) {
      if (!converged(std::move(record), outcome, state)) continue;
      result_.status = Status::converged;
      return std::move(result_);
    }
    saved_.restore(state);
    if (settings_.cutback && halvings_ < settings_.max_cutbacks && arc_ / 2.0 >= control_.min_increment * (1.0 - 1e-12)) {
      ++halvings_;
      arc_ /= 2.0;
      newton_.reset(state);
      record.load_factor = state.load_factor;  // the attempt's start
      recorder_.cut_back(std::move(record), step_failure_text(outcome.failure, model_));
      continue;
    }
    if (jump_across(state)) continue;
    give_up(std::move(record), outcome);
    return std::move(result_);
  }
  stop_at_step_limit(state);
  return std::move(result_);
}

bool ArcLengthStepping::converged(StepRecord record, const NewtonOutcome& outcome, State& state) {
  record.increment = state.load_factor - saved_.load_factor();
  ++converged_steps_;
  const int step = record.step;
  const Eigen::VectorXd& start = saved_.displacements();
  const std::optional<LimitBracket> bracket = limit_bracket(start, state);
  State peak;  // the extreme step's state, taken before recording lets its displacements go
  if (bracket) saved_.restore(peak);
  previous_start_lambda_ = saved_.load_factor();
  previous_step_ = step;
  // The step's increment steers the next predictor.
  constraint_.previous_increment.resize(dofs_.free_count());
  for (int eq = 0; eq < dofs_.free_count(); ++eq)
    constraint_.previous_increment[eq] = state.displacements[dofs_.dof(eq)] - start[dofs_.dof(eq)];
  constraint_.previous_load_increment = record.increment;
  halvings_ = 0;
  const double factor = std::clamp(std::sqrt(aim_iterations / std::max(1, outcome.iterations)), 0.5, 2.0);
  arc_ = std::clamp(arc_ * factor, control_.min_increment, control_.max_increment);
  ArcLengthMemory& memory = state.arc_length;  // kept with the state, for a restart from it
  memory.next_arc = arc_;
  memory.converged_steps = converged_steps_;
  memory.previous_increment = state.displacements - start;
  memory.previous_load_increment = constraint_.previous_load_increment;
  const bool reached = watching_ && crosses_until(start, state);
  State landed;  // the step's start, taken before recording lets its displacements go
  if (reached) saved_.restore(landed);
  recorder_.converged(std::move(record), outcome, state);
  if (reached) land(std::move(landed), state);
  else if (bracket) locate(*bracket, peak, state);
  return reached;
}

std::optional<LimitBracket> ArcLengthStepping::limit_bracket(const Eigen::VectorXd& start, const State& state) const {
  const Eigen::VectorXd& into = constraint_.previous_increment;  // the step before's increment
  if (!model_.contacts.empty() || std::isnan(previous_start_lambda_) || into.size() == 0) return std::nullopt;
  const double before = previous_start_lambda_, here = saved_.load_factor(), after = state.load_factor;
  const bool maximum = here > before && here > after, minimum = here < before && here < after;
  if (!maximum && !minimum) return std::nullopt;
  // A translation locates it (a rotation may be held only by a member's small bending stiffness:
  // a pin-jointed bar's end), a rotation only where no translation moves one way.
  Eigen::VectorXd out(dofs_.free_count()), translation(dofs_.free_count());
  for (int eq = 0; eq < dofs_.free_count(); ++eq) {
    out[eq] = state.displacements[dofs_.dof(eq)] - start[dofs_.dof(eq)];
    translation[eq] = dofs_.dof(eq) % dofs_per_node == rz ? 0.0 : 1.0;
  }
  int eq = monotone_equation(into, out, translation);
  if (eq < 0) eq = monotone_equation(into, out, Eigen::VectorXd::Ones(dofs_.free_count()) - translation);
  if (eq < 0) return std::nullopt;
  const double u = start[dofs_.dof(eq)];
  return LimitBracket{previous_step_, maximum, eq, {u - into[eq], u, u + out[eq]}, {before, here, after}};
}

void ArcLengthStepping::locate(const LimitBracket& bracket, const State& peak, State& state) {
  if (const std::optional<RefinedLimit> refined = refine_limit_point(bracket, peak, dofs_, newton_))
    result_.refined_limits.push_back(*refined);
  newton_.reset(state);
}

void ArcLengthStepping::land(State landed, State& state) {
  const double start_load_factor = landed.load_factor;
  newton_.reset(landed);
  PathConstraint land;
  if (control_.until == Control::Until::load_factor) {
    land.kind = PathConstraint::Kind::load_increment;
    land.load_increment = control_.until_value - start_load_factor;
  } else {
    land.kind = PathConstraint::Kind::displacement_target;
    land.equation = dofs_.equation(dofs_per_node * control_.until_node + control_.until_dof);
    land.target = control_.until_value;
  }
  const NewtonOutcome landing = newton_.step(land, landed);
  if (landing.status != Status::converged) {
    newton_.reset(state);  // keep the arc-length step that passed the target
    return;
  }
  StepRecord exact = recorder_.start(landing, 0);
  exact.increment = landed.load_factor - start_load_factor;
  exact.arc_length = 0.0;  // landed under load/displacement control
  state = std::move(landed);
  recorder_.replace_last(std::move(exact), landing, state);
}

bool ArcLengthStepping::jump_across(State& state) {
  // No arc reaches the path here: it jumps (a contact slipping off a beam's end springs the
  // beam back at one load factor).
  if (constraint_.previous_load_increment == 0.0) return false;
  newton_.reset(state);
  PathConstraint jump;
  jump.load_increment = constraint_.previous_load_increment;
  const NewtonOutcome across = newton_.step(jump, state);
  recorder_.started_from_newest(across, inertia_tells_stability(saved_.contacts()));
  if (across.status != Status::converged) {
    saved_.restore(state);
    newton_.reset(state);
    return false;
  }
  StepRecord crossed = recorder_.start(across, halvings_);
  crossed.increment = state.load_factor - saved_.load_factor();
  constraint_.previous_increment.resize(0);  // the jump is no direction to follow
  halvings_ = 0;
  arc_ = control_.initial_increment;
  ++converged_steps_;
  state.arc_length = {arc_, converged_steps_, Eigen::VectorXd(), constraint_.previous_load_increment};
  recorder_.converged(std::move(crossed), across, state);
  return true;
}

void ArcLengthStepping::give_up(StepRecord record, const NewtonOutcome& outcome) {
  record.load_factor = saved_.load_factor();
  result_.status = settings_.cutback ? Status::cutback_limit : outcome.status;
  RunFailure& failure = result_.failure;
  failure.kind = RunFailure::Kind::step_failed;
  failure.control = RunFailure::Control::arc_length;
  failure.step = record.step;
  failure.from = saved_.load_factor();
  failure.to = arc_;
  failure.cutbacks = halvings_;
  failure.step_failure = outcome.failure;
  result_.message = run_failure_text(failure, model_);
  recorder_.failed(std::move(record), failed_step_text(failure, model_));
}

void ArcLengthStepping::stop_at_step_limit(const State& state) {
  if (!watching_) {
    result_.status = Status::converged;
    return;
  }
  result_.status = Status::step_limit;
  RunFailure& failure = result_.failure;
  failure.kind = RunFailure::Kind::step_limit;
  failure.control = RunFailure::Control::arc_length;
  failure.max_steps = control_.max_steps;
  failure.until_value = control_.until_value;
  failure.until_now = watched(control_, state.load_factor, state.displacements);
  result_.message = run_failure_text(failure, model_);
}

void ArcLengthStepping::interrupt(const State& state) {
  result_.status = Status::interrupted;
  result_.failure = interruption(recorder_.next_step(), state.load_factor);
  result_.message = run_failure_text(result_.failure, model_);
}

}  // namespace

RunResult run_arc_length_stepping(const Model& model, const assembly::DofMap& dofs, NewtonSolver& newton,
                                  TsmProblem& problem, State& state, const StepObserver& observer, const StopRequest* stop) {
  ArcLengthStepping stepping(model, dofs, newton, problem, observer, stop);
  return stepping.run(state);
}

}  // namespace tsm::solver
