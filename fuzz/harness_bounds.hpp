#pragma once
// What the fuzz harnesses keep small, so that every input ends within a fraction of a second
// and no input can hang a fuzzer: a model's size is checked on its JSON before the reader meshes
// it, and the analysis read from it is cut to a few steps of a few iterations. The library's own
// limits are far larger (10⁷ elements, 10⁷ steps, 10⁵ iterations): a fuzzer spending minutes
// on one input that the library rightly accepts finds nothing, so the bounds are the harness's.

#include <nlohmann/json.hpp>

#include "tsmframe/model/model.hpp"

namespace tsm::fuzz {

inline constexpr double most_elements = 512;  ///< the members' divisions, summed
inline constexpr size_t most_nodes = 512;
inline constexpr int most_steps = 3;          ///< per leg of a load path; arc-length steps
inline constexpr size_t most_legs = 2;
inline constexpr int most_iterations = 12;
inline constexpr int most_cutbacks = 2;

/// Whether the model JSON would mesh into at most most_elements elements on most_nodes nodes
/// (as far as its JSON says: what the reader would refuse passes, for the reader to refuse).
bool small_model(const nlohmann::json& model);

/// Cuts the model's analysis, and each of its stages, to most_steps steps per leg, most_legs
/// legs, most_iterations iterations and most_cutbacks cutbacks.
void shorten_analysis(Model& model);

}  // namespace tsm::fuzz
