#pragma once
// The N, V, M diagrams of a step's elements (element/section_forces) from what its record holds:
// each element's forces, its chord at the step's displacements and the contact points on it.
// What results.json's "section_forces" and the Python module's diagrams show.

#include <vector>

#include "tsmframe/element/section_forces.hpp"
#include "tsmframe/model/model.hpp"
#include "tsmframe/solver/step_record.hpp"

namespace tsm::io {

/// Per element of the model, its stations at `step` (a step with state): its ends, and both sides
/// of every contact point between them (a point on a beam node acts on the node: it makes the
/// elements' end values differ there).
std::vector<std::vector<element::SectionStation>> section_diagrams(const Model& model, const solver::StepRecord& step);

}  // namespace tsm::io
