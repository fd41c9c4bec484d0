#include "tsmframe/solver/stages.hpp"

#include <utility>

#include "tsmframe/model/stage.hpp"
#include "tsmframe/solver/diagnosis.hpp"
#include "tsmframe/solver/run_stage.hpp"

namespace tsm::solver {
namespace {

/// The newest converged step a stage's result kept (0: none).
int last_converged_step(const RunResult& result) {
  for (auto it = result.steps.rbegin(); it != result.steps.rend(); ++it)
    if (it->converged) return it->step;
  return 0;
}

/// Moves one stage's result into the whole run's: steps numbered on from `first_step`.
void append_stage(RunResult& run, RunResult stage_result, int stage, const std::string& name, int steps_before) {
  for (StepRecord& record : stage_result.steps) {
    record.step += steps_before;
    record.stage = stage;
    run.steps.push_back(std::move(record));
  }
  for (LimitPoint p : stage_result.limit_points) run.limit_points.push_back({p.step + steps_before, p.maximum, p.load_factor});
  for (CriticalPoint p : stage_result.critical_points) {
    p.step += steps_before;
    run.critical_points.push_back(p);
  }
  for (const std::string& note : stage_result.notes) run.notes.push_back(in_stage_text(note, stage, name));
  run.status = stage_result.status;
  run.failure = stage_result.failure;
  if (stage_result.status != Status::converged) run.message = in_stage_text(stage_result.message, stage, name);
}

}  // namespace

RunResult run_stages(const Model& model, const StepObserver& observer, const StopRequest* stop) {
  RunResult run;
  State state;  // the unloaded state, then each stage's end
  StageStart start;
  int steps_before = 0;
  for (int s = 0; s < static_cast<int>(model.stages.size()); ++s) {
    const Model stage = stage_model(model, s, start);
    StepObserver numbered;
    if (observer)
      numbered = [&observer, s, steps_before](const StepRecord& record) {
        StepRecord copy = record;
        copy.step += steps_before;
        copy.stage = s;
        observer(copy);
      };
    RunResult result = run_stage(stage, state, numbered, stop);
    const int last = last_converged_step(result);
    run.stages.push_back({last > 0 ? last + steps_before : 0, state.load_factor, result.status});
    steps_before += last;
    append_stage(run, std::move(result), s, model.stages[s].name, steps_before - last);
    if (run.status != Status::converged) break;
    start.final_load_factors.push_back(state.load_factor);
    start.displacements = state.displacements;
  }
  return run;
}

}  // namespace tsm::solver
