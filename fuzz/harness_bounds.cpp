#include "harness_bounds.hpp"

#include <algorithm>
#include <cmath>

namespace tsm::fuzz {

bool small_model(const nlohmann::json& model) {
  if (!model.is_object()) return true;
  const auto nodes = model.find("nodes");
  if (nodes != model.end() && nodes->is_array() && nodes->size() > most_nodes) return false;
  const auto members = model.find("members");
  if (members == model.end() || !members->is_array()) return true;
  double elements = 0.0;
  for (const nlohmann::json& member : *members) {
    const auto divisions = member.is_object() ? member.find("divisions") : member.end();
    const bool counted = member.is_object() && divisions != member.end() && divisions->is_number();
    elements += counted ? std::max(1.0, divisions->get<double>()) : 1.0;  // NaN cannot be written in JSON
    if (!(elements <= most_elements)) return false;
  }
  return true;
}

void shorten_analysis(Model& model) {
  AnalysisSettings& analysis = model.analysis;
  // The analysis's control, and each stage's own (a stage of 4·10⁶ steps filled the fuzzer's
  // 2 GB with step records: the library accepts it within the machine's memory).
  const auto shorten = [](Control& control) {
    control.steps = std::min(control.steps, most_steps);
    if (control.path.size() > most_legs) control.path.resize(most_legs);
    control.max_steps = std::min(control.max_steps, most_steps);
  };
  shorten(analysis.control);
  for (Stage& stage : model.stages) shorten(stage.control);
  analysis.max_iterations = std::min(analysis.max_iterations, most_iterations);
  analysis.max_cutbacks = std::min(analysis.max_cutbacks, most_cutbacks);
}

}  // namespace tsm::fuzz
