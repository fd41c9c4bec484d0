#pragma once
// The model as it is drawn before any solve (`tsmframe plot`, Python's Model.plot; docs/format.md,
// "Model drawing"): the meshed nodes and elements, what holds them (supports, skew rollers,
// springs to the ground, hinges and end springs), what loads them stage by stage (nodal loads with
// the members' lumped into them, follower loads, pressures, prescribed displacements), and which
// nodes may touch which members. A JSON document (tsmframe-drawing/1) the drawing code
// (python/tsmframe/model_plot.py) reads; the mechanics stay here, the pictures there.

#include <optional>
#include <ostream>
#include <string>

#include "tsmframe/io/json_writer.hpp"
#include "tsmframe/model/model.hpp"

namespace tsm::io {

/// Writes what the drawing adds to the mesh (io/mesh_json.hpp) into the object `w` has open:
/// "supports", "springs", "load_cases" (per stage) and "contacts" — results.json carries them too,
/// so that its pictures draw the model the same way.
void write_model_symbols(JsonWriter& w, const Model& model);

/// Writes the drawing document of `model`; `mechanism`: the sentence naming the free motion
/// where the analysis starts (model::starting_mechanism), if the model is one.
void write_model_drawing(std::ostream& out, const Model& model, const std::optional<std::string>& mechanism);

/// The same as text.
std::string model_drawing(const Model& model, const std::optional<std::string>& mechanism);

}  // namespace tsm::io
