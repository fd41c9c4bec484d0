#pragma once
// A model file's "analysis" (docs/format.md): the control (load, displacement, arc-length), the
// convergence settings, the output selection and the monitored nodes; and whether the states the
// output selection keeps fit in memory.

#include <functional>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "tsmframe/model/model.hpp"

namespace tsm::io {

/// A node reference written at a JSON path, resolved to a node index (throws InputError).
using NodeResolver = std::function<int(const nlohmann::json& value, const std::string& path)>;

/// What a control is read against: the model's nodes, the dofs held where it runs (the
/// supports, and a stage's prescribed dofs), how node references resolve.
struct ControlContext {
  const Model& model;
  const std::vector<bool>& constrained;
  const NodeResolver& node;
  /// The path starts from the unloaded state (a displacement control's target ≠ 0); false for a
  /// later stage, which starts where the one before ended.
  bool at_rest = true;
};

/// Reads a "control" object at `path` (a controlled or watched dof must be free). Throws InputError.
void read_control(const nlohmann::json& c, const std::string& path, const ControlContext& at, Control& control);
/// Reads an "output" selection at `path`. Throws InputError.
void read_output(const nlohmann::json& o, const std::string& path, OutputSelection& out);

/// Reads the object at "analysis" into model.analysis, the model's nodes and constraints known
/// (a controlled dof must be free). Throws InputError.
void read_analysis_settings(const nlohmann::json& analysis, Model& model, const NodeResolver& node);

/// Refuses (at "analysis.output") an output selection under load or displacement control whose
/// kept states would take more than 8 GB.
void check_kept_states(const Model& model);

}  // namespace tsm::io
