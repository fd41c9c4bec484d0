#pragma once
// Every sentence a failed run prints, built from the facts of failure.hpp: why a step failed,
// why the run stopped, and the hints that name a likely cause (elements too short, a cable
// drawn straight, a limit point).

#include <string>

#include "tsmframe/model/model.hpp"
#include "tsmframe/solver/failure.hpp"

namespace tsm::solver {

/// A ratio as a reader takes it in: 233, not 2.3e+02; 0.25 to two digits.
std::string format_ratio(double ratio);

/// Why a Newton step failed: "… at iteration n", the structure's own facts first.
std::string step_failure_text(const StepFailure& failure, const Model& model);
/// What the record of the run's last (failed) step says.
std::string failed_step_text(const RunFailure& failure, const Model& model);
/// The run's message: where it stopped, why, and what may help.
std::string run_failure_text(const RunFailure& failure, const Model& model);
/// A stage's displacement control that starts at its target: nothing to drive.
std::string control_at_target_text(const Model& stage);
/// A stage's sentence (its run's message or a note) said of that stage (`stage`: its index).
std::string in_stage_text(const std::string& text, int stage, const std::string& name);

}  // namespace tsm::solver
