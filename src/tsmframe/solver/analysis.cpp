#include "tsmframe/solver/analysis.hpp"

#include "tsmframe/solver/buckling.hpp"
#include "tsmframe/solver/path_notes.hpp"
#include "tsmframe/solver/run_stage.hpp"
#include "tsmframe/solver/stages.hpp"

namespace tsm::solver {

RunResult run_analysis(const Model& model, const StepObserver& observer, const StopRequest* stop, const RestartPoint* from) {
  if (!model.stages.empty()) return run_stages(model, observer, stop, from);
  State state;
  if (!from) {
    Buckling buckling = linear_buckling(model, model.analysis.buckling_modes);
    RunResult result = run_stage(model, state, observer, stop);
    if (buckling.unresolved) result.notes.push_back(unresolved_buckling_note(model.analysis.buckling_modes, buckling.modes.size()));
    result.buckling = std::move(buckling);
    return result;
  }
  state = from->state;
  Model restarted = model;
  restarted.analysis.first_step = from->step + 1;  // numbered on from the kept step
  return run_stage(restarted, state, observer, stop);
}

}  // namespace tsm::solver
