#pragma once
// A mechanism among hinges found before any step: the elements' own stiffness at the unloaded
// state leaves a motion free (three hinges in a line, a four-hinged portal), which the supports'
// check (model/mechanism), looking at connected parts as rigid bodies, cannot see. What a run finds
// when its first step meets the singular tangent (TsmProblem::explain), asked up front — for the
// model's drawing.

#include <optional>
#include <string>

#include "tsmframe/model/model.hpp"

namespace tsm::solver {

/// The sentence naming the free motion ("the structure is a mechanism: unloaded, it can move …"),
/// or none where the unloaded tangent is regular. Assembles and factorises it once.
std::optional<std::string> unloaded_mechanism(const Model& model);

/// What makes a model a mechanism as drawn, if anything: the supports' check
/// (model::starting_mechanism; `at_supports`, its JSON path "supports"), then the hinges'
/// (unloaded_mechanism; not with stages, whose first stage may hold more).
struct Mechanism {
  std::string text;
  bool at_supports = false;
};
std::optional<Mechanism> drawn_mechanism(Model& model);

}  // namespace tsm::solver
