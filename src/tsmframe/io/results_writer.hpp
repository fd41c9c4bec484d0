#pragma once
// results.json and steps.csv (docs/format.md, "tsmframe-results/1").

#include <ostream>
#include <string>

#include "tsmframe/model/model.hpp"
#include "tsmframe/solver/step_record.hpp"

namespace tsm::io {

/// What results.json holds beside what it always does.
struct ResultsOptions {
  /// Each step with state gets "curves": per element id its deflected curve's curve_segments + 1
  /// points (io/element_curves) as [x0, y0, x1, y1, …] in current coordinates (`--curves`).
  bool curves = false;
};

void write_results_json(std::ostream& out, const Model& model, const solver::RunResult& result,
                        const ResultsOptions& options = {});
void write_steps_csv(std::ostream& out, const Model& model, const solver::RunResult& result);

/// Writes DIR/results.json and DIR/steps.csv, creating DIR if needed (a run's DIR is the
/// temporary directory of an OutputDirectory: the files appear with the commit). Throws
/// SystemError (the path, the OS's reason) where the system fails.
void write_results(const std::string& directory, const Model& model, const solver::RunResult& result,
                   const ResultsOptions& options = {});

}  // namespace tsm::io
