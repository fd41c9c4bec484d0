#pragma once
// The meshed model's nodes and elements as JSON — one writer for results.json and the model
// drawing (docs/format.md, "results.json": nodes, elements).

#include "tsmframe/io/json_writer.hpp"
#include "tsmframe/model/model.hpp"

namespace tsm::io {

/// Writes the keys "nodes" ([{id, x, y}]) and "elements" ([{id, nodes, element, member,
/// release?, end_springs?}]) into the object `w` has open.
void write_mesh(JsonWriter& w, const Model& model);

}  // namespace tsm::io
