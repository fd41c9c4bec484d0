#pragma once
// A restart point read back (`tsmframe run MODEL.json --from DIR/results.json[#STEP]`): a
// converged step an earlier run of the same model kept with its state (results.json's step
// "state"; docs/format.md, "Restart").

#include <nlohmann/json_fwd.hpp>
#include <string>

#include "tsmframe/model/model.hpp"
#include "tsmframe/solver/restart.hpp"

namespace tsm::io {

/// Step `step` of `results` (0: the newest step with state), checked to come from a run of
/// `model` (the same nodes, elements and contacts, and under arc-length control where the model's
/// control is one). Throws InputError at the JSON path at fault.
solver::RestartPoint read_restart(const nlohmann::json& results, int step, const Model& model);

/// The same of a file "PATH" or "PATH#STEP" (the caller names the file with the error).
solver::RestartPoint read_restart_file(const std::string& where, const Model& model);

}  // namespace tsm::io
