#include "tsmframe/solver/analysis.hpp"

#include "tsmframe/solver/run_stage.hpp"
#include "tsmframe/solver/stages.hpp"

namespace tsm::solver {

RunResult run_analysis(const Model& model, const StepObserver& observer, const StopRequest* stop) {
  if (!model.stages.empty()) return run_stages(model, observer, stop);
  State state;
  return run_stage(model, state, observer, stop);
}

}  // namespace tsm::solver
