#include "tsmframe/solver/load_stepping.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "tsmframe/solver/diagnosis.hpp"
#include "tsmframe/solver/stability.hpp"
#include "tsmframe/solver/step_start.hpp"
#include "tsmframe/solver/tsm_problem.hpp"

namespace tsm::solver {
namespace {

constexpr double contact_at_element_end = 1e-3;  // α this close to 0 or 1: the contact point is at the element's end
constexpr int steps_below_failure = 3;  // converged steps just below an increment that failed before it is tried again
constexpr double limit_point_stiffness = 0.1;  // a current stiffness below this × the first step's: near a maximum

/// The path parameter t runs from 0 to the number of legs (1 unless a load path is given): λ
/// under load control, the fraction of the target under displacement control, piecewise linear
/// between the path's points. Steps end on the grid k/N of each leg; cutback halves within a
/// grid cell.
class LoadStepping {
 public:
  LoadStepping(const Model& model, const assembly::DofMap& dofs, NewtonSolver& newton, TsmProblem& problem,
               const StepObserver& observer, const StopRequest* stop)
      : model_(model), stop_(stop), settings_(model.analysis), control_(settings_.control), newton_(newton), problem_(problem),
        recorder_(model, problem, observer, result_, true), by_displacement_(control_.type == ControlType::displacement),
        nominal_(1.0 / control_.steps), increment_(nominal_) {
    if (by_displacement_) {
      constraint_.kind = PathConstraint::Kind::displacement_target;
      constraint_.equation = dofs.equation(dofs_per_node * control_.node + control_.dof);
    }
    points_.push_back(0.0);
    if (control_.path.empty()) points_.push_back(1.0);
    else points_.insert(points_.end(), control_.path.begin(), control_.path.end());
    legs_ = static_cast<int>(points_.size()) - 1;
  }

  RunResult run(State& state);

 private:
  /// The next attempt: its size dt along t and where it ends.
  struct Attempt {
    double dt = 0.0, t_end = 0.0;
    bool reaches_grid = false;
  };
  Attempt next_attempt() const;
  /// λ (or the fraction of the controlled dof's target) at path parameter t.
  double value(double t) const {
    const int leg = std::min(static_cast<int>(t), legs_ - 1);
    return points_[leg] + (t - leg) * (points_[leg + 1] - points_[leg]);
  }
  /// The path quantity the step's size measures at t: λ, or the controlled dof's value.
  double path_quantity(double t) const { return by_displacement_ ? control_.start + value(t) * span() : value(t); }
  /// What the path parameter's value scales: 1 (λ), or the controlled dof's travel.
  double span() const { return by_displacement_ ? control_.target - control_.start : 1.0; }
  /// Under load control, when a step turned the path unstable: the bifurcation's load factor
  /// (stability.hpp), the attempt in progress kept and evaluated again.
  void check_bifurcation(State& state);
  void converged(const Attempt& attempt, StepRecord record, const NewtonOutcome& outcome, State& state);
  /// After a failed attempt (state restored to the step's start): whether cutback tries again smaller.
  bool cut_back(const Attempt& attempt, const NewtonOutcome& outcome, State& state);
  /// The run stops at the failed attempt: its status, message and last record.
  void give_up(const Attempt& attempt, StepRecord record, const NewtonOutcome& outcome, const State& state);
  /// The run stops on request before the next attempt, `state` the newest converged step's.
  void interrupt(const State& state);

  const Model& model_;
  const StopRequest* stop_;
  const AnalysisSettings& settings_;
  const Control& control_;
  NewtonSolver& newton_;
  TsmProblem& problem_;
  RunResult result_;
  Recorder recorder_;
  const bool by_displacement_;
  PathConstraint constraint_;
  std::vector<double> points_;
  int legs_ = 1;
  const double nominal_;
  double t_ = 0.0, increment_;
  // After a cutback the increment doubles back step by step, but an increment that failed is
  // tried again only after steps_below_failure steps have converged just below it: where the
  // path stays hard, every step tried it first and failed (a beam rolled 60 rad in one step,
  // 60 EB elements: 133 failed attempts in 128 steps), each failure costing up to
  // max_iterations iterations.
  double failed_increment_ = INFINITY;
  int below_failure_ = 0;
  int halvings_ = 0, grid_index_ = 0;
  StepStart saved_;  // reused: no allocation per step
  // The current stiffness parameter |Δλ| / ‖ΔD‖ of the first iterate (the tangent's) at the
  // first step's start and at the newest (newest_at_; Bergan): near a largest load it falls
  // towards zero. A converged step's secant would not: a deep arch's last step below its maximum
  // still had a quarter of the first step's.
  double first_stiffness_ = 0.0;
  /// The current stiffness at the two newest converged states a step started from, with their
  /// load factors: near a smooth maximum k² falls linearly with λ, so the two place it.
  struct StiffnessAt {
    double load_factor = 0.0, stiffness = 0.0;
  };
  StiffnessAt newest_at_, before_at_;
  bool maximum_within(double load_factor) const;
};

/// Whether k² (the current stiffness's square), run on linearly through the two newest
/// converged states, reaches zero before `load_factor`: a maximum within the step to it.
bool LoadStepping::maximum_within(double load_factor) const {
  const double k0 = before_at_.stiffness, k1 = newest_at_.stiffness;
  const double dl = newest_at_.load_factor - before_at_.load_factor;
  if (!(k0 > 0.0 && k1 > 0.0 && dl > 0.0 && k1 < k0)) return false;
  return newest_at_.load_factor + k1 * k1 * dl / (k0 * k0 - k1 * k1) <= load_factor;
}

LoadStepping::Attempt LoadStepping::next_attempt() const {
  const double next_grid = static_cast<double>(grid_index_ + 1) / control_.steps;
  double dt = std::min(increment_, next_grid - t_);
  if (next_grid - t_ - dt < 1e-9 * nominal_) dt = next_grid - t_;
  const bool reaches_grid = dt == next_grid - t_;
  return {dt, reaches_grid ? next_grid : t_ + dt, reaches_grid};
}

RunResult LoadStepping::run(State& state) {
  const int grid_steps = control_.steps * legs_;
  // A run restarted along its path (restart.hpp) goes on from where that state was.
  t_ = state.path_parameter;
  grid_index_ = static_cast<int>(std::floor(t_ * control_.steps + 1e-9));
  recorder_.start_from(state);
  while (grid_index_ < grid_steps) {
    if (stop_requested(stop_)) {
      interrupt(state);
      return std::move(result_);
    }
    const Attempt attempt = next_attempt();
    if (by_displacement_) constraint_.target = path_quantity(attempt.t_end);
    else constraint_.load_increment = value(attempt.t_end) - state.load_factor;

    saved_.take(state, recorder_.newest_displacements());
    const bool tells_stability = inertia_tells_stability(state.contacts);
    const NewtonOutcome outcome = newton_.step(constraint_, state);
    recorder_.started_from_newest(outcome, tells_stability);
    if (!by_displacement_) check_bifurcation(state);
    StepRecord record = recorder_.start(outcome, halvings_);
    record.increment = (value(attempt.t_end) - value(t_)) * span();
    if (!by_displacement_ && outcome.start_stiffness > 0.0) {  // each attempt starts from a converged state
      if (first_stiffness_ == 0.0) first_stiffness_ = outcome.start_stiffness;
      if (saved_.load_factor() != newest_at_.load_factor) before_at_ = newest_at_;
      newest_at_ = {saved_.load_factor(), outcome.start_stiffness};
    }
    if (outcome.status == Status::converged) {
      converged(attempt, std::move(record), outcome, state);
      continue;
    }
    saved_.restore(state);
    if (cut_back(attempt, outcome, state)) {
      record.load_factor = state.load_factor;  // the attempt's start
      recorder_.cut_back(std::move(record), step_failure_text(outcome.failure, model_));
      continue;
    }
    give_up(attempt, std::move(record), outcome, state);
    return std::move(result_);
  }
  recorder_.finish(state);
  result_.status = Status::converged;
  return std::move(result_);
}

void LoadStepping::check_bifurcation(State& state) {
  const auto [newest, previous] = newest_converged_two(result_.steps);
  if (!turned_unstable(newest, previous, result_)) return;
  State from;  // the newest step's state; the attempt in progress is kept and evaluated again
  saved_.restore(from);
  const State attempt = state;
  locate_bifurcation(*newest, *previous, from, newton_, problem_, result_);
  state = attempt;
  newton_.reset(state);
}

void LoadStepping::converged(const Attempt& attempt, StepRecord record, const NewtonOutcome& outcome, State& state) {
  t_ = state.path_parameter = attempt.t_end;
  record.path_parameter = t_;
  if (attempt.reaches_grid) ++grid_index_;
  halvings_ = 0;
  const double grown = std::min(2.0 * increment_, nominal_);
  if (grown < failed_increment_ * (1.0 - 1e-12)) increment_ = grown;
  else if (++below_failure_ >= steps_below_failure) increment_ = grown, failed_increment_ = INFINITY;
  saved_.release();
  recorder_.converged(std::move(record), outcome, state);
}

bool LoadStepping::cut_back(const Attempt& attempt, const NewtonOutcome& outcome, State& state) {
  // The smallest increment cutback may try: max_cutbacks halvings of the nominal step. Without
  // it, steps that keep converging ever closer to a barrier would never end.
  const double smallest = std::ldexp(nominal_, -settings_.max_cutbacks);
  if (!settings_.cutback || independent_of_step_size(outcome.failure) || halvings_ >= settings_.max_cutbacks ||
      attempt.dt / 2.0 < smallest * (1.0 - 1e-12))
    return false;
  ++halvings_;
  increment_ = attempt.dt / 2.0;
  failed_increment_ = attempt.dt;
  below_failure_ = 0;
  newton_.reset(state);
  return true;
}

void LoadStepping::give_up(const Attempt& attempt, StepRecord record, const NewtonOutcome& outcome, const State& state) {
  record.load_factor = by_displacement_ ? saved_.load_factor() : value(attempt.t_end);
  result_.status = settings_.cutback && !independent_of_step_size(outcome.failure) ? Status::cutback_limit : outcome.status;
  // A largest load: cut back and still failing, the current stiffness down to a tenth of its
  // first step's, and the tangent — positive definite at the step's start — indefinite at its
  // iterates. Load control cannot pass it. Not where a contact point stands at the end of its
  // element (state is the step's start again): the edge, where the contact element's stiffness
  // changes abruptly, is then as likely the cause (Fig. 7's `paper` rows, which cannot hand over).
  const auto at_element_end = [&] {
    return std::any_of(state.contacts.begin(), state.contacts.end(), [](const contact::ContactState& c) {
      return c.active && std::min(c.alpha, 1.0 - c.alpha) < contact_at_element_end;
    });
  };
  // Cut back: halved in this attempt, or already at the smallest size since an earlier failure
  // (its halvings count restarts once a step converges).
  const bool cut = halvings_ > 0 || attempt.dt < nominal_ * (1.0 - 1e-9);
  // Near a maximum the stiffness is low, or — where the maximum is flat and the smallest step
  // reaches past it — falls to nil within the step.
  const bool ahead = maximum_within(value(attempt.t_end));
  const bool limit_point = !by_displacement_ && cut && outcome.start_negative_pivots == 0 &&
                           outcome.most_negative_pivots > 0 && first_stiffness_ > 0.0 &&
                           (newest_at_.stiffness < limit_point_stiffness * first_stiffness_ || ahead) &&
                           !at_element_end();
  RunFailure& failure = result_.failure;
  failure.kind = RunFailure::Kind::step_failed;
  failure.control = by_displacement_ ? RunFailure::Control::controlled_displacement : RunFailure::Control::load_factor;
  failure.step = record.step;
  failure.from = path_quantity(t_);
  failure.to = path_quantity(attempt.t_end);
  failure.cutbacks = halvings_;
  failure.step_failure = outcome.failure;
  failure.max_cutbacks = settings_.max_cutbacks;
  // No halving left: the step is at the smallest size, reached now or since an earlier failure,
  // with halvings in a row to spare (else cutbacks_exhausted says it).
  failure.smallest_step = settings_.cutback && halvings_ < settings_.max_cutbacks &&
                          attempt.dt / 2.0 < std::ldexp(nominal_, -settings_.max_cutbacks) * (1.0 - 1e-12);
  if (limit_point) {
    failure.limit_point_stiffness = newest_at_.stiffness / first_stiffness_;
    failure.limit_point_ahead = ahead;
  }
  failure.cutbacks_exhausted = settings_.cutback && halvings_ >= settings_.max_cutbacks && !limit_point &&
                               outcome.failure.reason != StepFailure::Reason::loads_unresolvable;
  failure.first_step = state.load_factor == 0.0;  // the path's first step
  result_.message = run_failure_text(failure, model_);
  recorder_.finish(state);  // state is the newest converged step's again
  recorder_.failed(std::move(record), failed_step_text(failure, model_));
}

void LoadStepping::interrupt(const State& state) {
  recorder_.finish(state);
  result_.status = Status::interrupted;
  result_.failure = interruption(recorder_.next_step(), state.load_factor);
  result_.message = run_failure_text(result_.failure, model_);
}

}  // namespace

RunResult run_load_stepping(const Model& model, const assembly::DofMap& dofs, NewtonSolver& newton, TsmProblem& problem,
                            State& state, const StepObserver& observer, const StopRequest* stop) {
  LoadStepping stepping(model, dofs, newton, problem, observer, stop);
  return stepping.run(state);
}

}  // namespace tsm::solver
