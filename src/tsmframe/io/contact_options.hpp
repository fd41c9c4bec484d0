#pragma once
// A contact entry's options for its law (FORMAT: "frame", "normal", "edge", "max_stiffness_ratio",
// "sliding_tangent", "gap"), read into its ContactSpec, each checked with its JSON path. What the
// entry touches (node, nodes, members, between) and its beam theory are the model reader's.

#include <nlohmann/json.hpp>
#include <string>

#include "tsmframe/model/model.hpp"

namespace tsm::io {

/// Reads the options of contact entry `entry` (at `path`) into `spec`; throws InputError.
void read_contact_law_options(const nlohmann::json& entry, const std::string& path, ContactSpec& spec);

}  // namespace tsm::io
