#include "tsmframe/solver/analysis.hpp"

#include "tsmframe/solver/buckling.hpp"
#include "tsmframe/solver/path_notes.hpp"
#include "tsmframe/solver/run_stage.hpp"
#include "tsmframe/solver/stages.hpp"

namespace tsm::solver {

namespace {

/// The converged state buckling is estimated from where the model asks for a state of its run:
/// the last converged one, or step `buckling_step` (none where it did not converge).
const StepRecord* buckling_record(const AnalysisSettings& settings, const RunResult& result) {
  for (auto s = result.steps.rbegin(); s != result.steps.rend(); ++s) {
    if (!s->converged || !s->has_state) continue;
    if (settings.buckling_at == AnalysisSettings::BucklingAt::end || s->step == settings.buckling_step) return &*s;
  }
  return nullptr;
}

/// Linearised buckling as the model asks, after its run where it asks for a state of the run;
/// a note where that state was not reached or a mode was not resolved.
void add_buckling(const Model& model, Buckling unloaded, RunResult& result) {
  const AnalysisSettings& settings = model.analysis;
  Buckling buckling = std::move(unloaded);
  if (settings.buckling_at != AnalysisSettings::BucklingAt::unloaded) {
    if (const StepRecord* s = buckling_record(settings, result)) {
      const BucklingState at{s->step, s->load_factor, s->displacements, s->chord_rotations};
      buckling = linear_buckling(model, settings.buckling_modes, &at);
    } else {
      result.notes.push_back(unreached_buckling_note(settings.buckling_at == AnalysisSettings::BucklingAt::step ? settings.buckling_step : 0));
    }
  }
  if (buckling.unresolved) result.notes.push_back(unresolved_buckling_note(settings.buckling_modes, buckling.modes.size()));
  result.buckling = std::move(buckling);
}

}  // namespace

RunResult run_analysis(const Model& model, const StepObserver& observer, const StopRequest* stop, const RestartPoint* from) {
  if (!model.stages.empty()) return run_stages(model, observer, stop, from);
  State state;
  if (!from) {
    // At the unloaded state before the run: a failing run still reports it.
    const bool unloaded = model.analysis.buckling_at == AnalysisSettings::BucklingAt::unloaded;
    Buckling before = unloaded ? linear_buckling(model, model.analysis.buckling_modes) : Buckling{};
    RunResult result = run_stage(model, state, observer, stop);
    if (model.analysis.buckling_modes > 0) add_buckling(model, std::move(before), result);
    return result;
  }
  state = from->state;
  Model restarted = model;
  restarted.analysis.first_step = from->step + 1;  // numbered on from the kept step
  return run_stage(restarted, state, observer, stop);
}

}  // namespace tsm::solver
