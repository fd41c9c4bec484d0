#pragma once
// Appends a run's step records: a converged step gets its state (only the newest keeps it unless
// the output selection wants it), every step goes to the observer.

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "tsmframe/model/mechanism.hpp"
#include "tsmframe/model/model.hpp"
#include "tsmframe/solver/newton.hpp"
#include "tsmframe/solver/tsm_problem.hpp"
#include "tsmframe/solver/state.hpp"
#include "tsmframe/solver/step_record.hpp"

namespace tsm::solver {

class Recorder {
 public:
  /// With `defer_forces`, a step that the output selection drops again once a later step
  /// converges gets its element forces (a pass over the elements) only if it stays the newest:
  /// finish() adds them. Without an observer only: an observer sees every step whole.
  Recorder(const Model& model, const TsmProblem& problem, const StepObserver& observer, RunResult& result,
           bool defer_forces = false);

  int next_step() const { return model_.analysis.first_step + static_cast<int>(result_.steps.size()); }
  /// A record for the outcome of one attempt.
  StepRecord start(const NewtonOutcome& outcome, int cutbacks) const;
  void converged(StepRecord record, const NewtonOutcome& outcome, const State& state);
  /// An attempt that started from the newest converged step's state factorised the tangent there
  /// first: its inertia is that step's, where it tells the stability (`tells`).
  void started_from_newest(const NewtonOutcome& outcome, bool tells);
  /// Displacements of the newest converged step, held in its record until a later step
  /// converges (null before the first converged step, and where a skew roller's frame makes
  /// the state's differ from the record's global ones).
  const Eigen::VectorXd* newest_displacements() const {
    return last_with_state_ >= 0 && !problem_.turns_frames() ? &result_.steps[last_with_state_].displacements : nullptr;
  }
  /// The state the run starts from: the first step's largest move is measured from it (an
  /// earlier stage's end, a restart; nil when unloaded).
  void start_from(const State& state);
  /// Replaces the newest converged step (arc-length landing exactly on its `until`).
  void replace_last(StepRecord record, const NewtonOutcome& outcome, const State& state);
  /// At the end of the run, with `state` the newest converged step's: its deferred element forces.
  void finish(const State& state);
  void failed(StepRecord record, const std::string& message);
  /// An attempt that failed and is tried again smaller: to the observer only (why, in
  /// `message`), so a long run tells where and why its steps are cut back.
  void cut_back(StepRecord record, const std::string& message) const;

 private:
  /// Hands a record just kept to the observer, then frees what only the observer reads.
  void observe(StepRecord& record) const;
  /// Whether `record`'s state (`state`, just evaluated) is a neutral equilibrium the supports
  /// allow (model/mechanism's SupportedParts): marks it and keeps its free motion.
  void take_neutral(StepRecord& record, const State& state);

  const Model& model_;
  const TsmProblem& problem_;
  const StepObserver& observer_;
  RunResult& result_;
  int last_with_state_ = -1;
  bool defer_forces_ = false;
  std::vector<int> moved_dofs_;
  SupportedParts supported_;  ///< for the neutral equilibria the supports allow at a converged state
  Eigen::VectorXd start_;  ///< start_from's displacements (empty: nil)
  bool forces_pending_ = false;  ///< the newest converged step still lacks its element forces
};

}  // namespace tsm::solver
