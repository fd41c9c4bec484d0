#pragma once
// A model file's "supports" (docs/format.md): the dofs each fixes, and skew rollers — a node
// rolling along an inclined plane, held normal to it (Model::skew_rollers).

#include <nlohmann/json_fwd.hpp>
#include <set>
#include <string>
#include <vector>

#include "tsmframe/io/analysis_reader.hpp"
#include "tsmframe/model/model.hpp"

namespace tsm::io {

/// Reads "supports" into Model::constrained and Model::skew_rollers; returns the JSON path of each
/// skew roller's "roller" (in Model::skew_rollers' order). Throws InputError.
std::vector<std::string> read_supports(const nlohmann::json& document, const NodeResolver& node, Model& model);

/// Once everything is read: a skew roller's node has no other support of its translations, no
/// prescribed displacement (`prescribed_nodes`) and no controlled or watched translation — its
/// translations are solved for along and across the plane. Throws InputError at the roller's
/// path (`roller_paths`, from read_supports).
void check_skew_rollers(const Model& model, const std::vector<std::string>& roller_paths, const std::set<int>& prescribed_nodes);

}  // namespace tsm::io
