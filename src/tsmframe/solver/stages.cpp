#include "tsmframe/solver/stages.hpp"

#include <optional>
#include <string>
#include <utility>

#include "tsmframe/contact/contact_state.hpp"
#include "tsmframe/model/stage.hpp"
#include "tsmframe/solver/diagnosis.hpp"
#include "tsmframe/solver/run_stage.hpp"

namespace tsm::solver {
namespace {

/// The newest converged step a result kept (0: none).
int last_converged_step(const RunResult& result) {
  for (auto it = result.steps.rbegin(); it != result.steps.rend(); ++it)
    if (it->converged) return it->step;
  return 0;
}

/// Where the dofs stage `s` prescribes or controls stand at its start (what a restart within
/// it needs to build its model again).
std::vector<std::pair<int, double>> stage_start_values(const Model& model, int s, const StageStart& start) {
  std::vector<int> dofs;
  for (const PrescribedTarget& p : model.stages[s].prescribed) dofs.push_back(p.dof);
  const Control& control = model.stages[s].control;
  if (control.type == ControlType::displacement) dofs.push_back(dofs_per_node * control.node + control.dof);
  std::vector<std::pair<int, double>> values;
  for (const int dof : dofs) values.emplace_back(dof, start.displacements.size() > 0 ? start.displacements[dof] : 0.0);
  return values;
}

/// A stage whose displacement control starts at its target has no path: said of the stage.
std::optional<std::string> nothing_to_drive(const Model& stage, int s, const std::string& name) {
  const Control& control = stage.analysis.control;
  if (control.type != ControlType::displacement || control.target != control.start) return std::nullopt;
  return in_stage_text(control_at_target_text(stage), s, name);
}

/// Moves one stage's result into the whole run's (its steps already numbered on).
void append_stage(RunResult& run, RunResult stage_result, int stage, const std::string& name, const StageStart& start,
                  const std::vector<std::pair<int, double>>& stage_start) {
  for (StepRecord& record : stage_result.steps) {
    if (record.has_state) record.stage_start = stage_start, record.stage_load_factors = start.final_load_factors;
    run.steps.push_back(std::move(record));
  }
  run.limit_points.insert(run.limit_points.end(), stage_result.limit_points.begin(), stage_result.limit_points.end());
  run.critical_points.insert(run.critical_points.end(), stage_result.critical_points.begin(), stage_result.critical_points.end());
  run.neutral_steps.insert(run.neutral_steps.end(), stage_result.neutral_steps.begin(), stage_result.neutral_steps.end());
  run.rounded_steps.insert(run.rounded_steps.end(), stage_result.rounded_steps.begin(), stage_result.rounded_steps.end());
  for (const std::string& note : stage_result.notes) run.notes.push_back(in_stage_text(note, stage, name));
  run.status = stage_result.status;
  run.failure = stage_result.failure;
  if (stage_result.status != Status::converged) run.message = in_stage_text(stage_result.message, stage, name);
}

}  // namespace

RunResult run_stages(const Model& model, const StepObserver& observer, const StopRequest* stop, const RestartPoint* from) {
  RunResult run;
  State state;  // the unloaded state, then each stage's end
  StageStart start;
  int steps_before = 0, first = 0;
  if (from) {  // within stage `first`, whose start is the restart point's own but at its prescribed dofs
    state = from->state;
    first = from->stage;
    steps_before = from->step;
    start.final_load_factors = from->final_load_factors;
    start.displacements = state.displacements;
    for (const auto& [dof, value] : from->stage_start) start.displacements[dof] = value;
  }
  for (int s = first; s < static_cast<int>(model.stages.size()); ++s) {
    Model stage = stage_model(model, s, start);
    stage.analysis.first_step = steps_before + 1;  // numbered on through the stages
    stage.analysis.stage = s;
    if (s > first || !from) {  // the stage's own λ starts at nil, its path afresh
      state.load_factor = state.path_parameter = 0.0;
      state.arc_length = ArcLengthMemory{};
    }
    const std::vector<char>& off = model.stages[s].contact_off;
    for (size_t c = 0; c < off.size() && c < state.contacts.size(); ++c)
      if (off[c]) state.contacts[c] = contact::ContactState{};  // let go; its references restored when it is back
    if (const std::optional<std::string> note = nothing_to_drive(stage, s, model.stages[s].name)) {
      run.notes.push_back(*note);
      run.stages.push_back({s, 0, 0.0, Status::converged});
      start.final_load_factors.push_back(0.0);
      continue;
    }
    RunResult result = run_stage(stage, state, observer, stop);
    const int last = last_converged_step(result);
    run.stages.push_back({s, last, state.load_factor, result.status});
    if (last > 0) steps_before = last;
    append_stage(run, std::move(result), s, model.stages[s].name, start, stage_start_values(model, s, start));
    if (run.status != Status::converged) break;
    start.final_load_factors.push_back(state.load_factor);
    start.displacements = state.displacements;
  }
  return run;
}

}  // namespace tsm::solver
