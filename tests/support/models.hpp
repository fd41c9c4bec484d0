#pragma once
// Model files for the tests, built as JSON so every test also goes through the file contract.

#include <nlohmann/json.hpp>
#include <string>

#include "tsmframe/io/model_reader.hpp"
#include "tsmframe/solver/analysis.hpp"

namespace tsm::test {

using nlohmann::json;

/// A straight beam of length L along x, from node 1 at (0, 0) to node 2 at (L, 0).
struct BeamSpec {
  double L = 1.0;
  double E = 1.0, G = 0.5;
  double A = 1e4, I = 1.0, shear_area = 1e3;
  int divisions = 10;
  const char* element = "euler-bernoulli";
};

inline json beam_model(const BeamSpec& b) {
  return json{
      {"materials", {{"m", {{"E", b.E}, {"G", b.G}}}}},
      {"sections", {{"s", {{"A", b.A}, {"I", b.I}, {"shear_area", b.shear_area}}}}},
      {"nodes", json::array({{{"id", 1}, {"x", 0.0}, {"y", 0.0}}, {{"id", 2}, {"x", b.L}, {"y", 0.0}}})},
      {"members", json::array({{{"from", 1}, {"to", 2}, {"divisions", b.divisions}, {"element", b.element},
                                {"material", "m"}, {"section", "s"}}})},
      {"analysis", {{"control", {{"type", "load"}, {"steps", 1}}}}},
  };
}

/// Reads the model file `m` into `model` and runs it.
inline solver::RunResult run(const json& m, Model& model) {
  model = io::read_model(m);
  return solver::run_analysis(model);
}

/// A pinned beam (10 m, `upper` Timoshenko elements, EI 2e4) drawn 1 cm above a simply supported
/// one (`lower` elements, EI 4e6: 200 × as stiff), every node of it a contact node on the lower
/// beam (one entry, gap 5 cm), under a uniform load fy (N/m) in `steps` steps
/// (examples/beam-pressed-onto-beam.json has 100 over 300).
inline json pressed_beams(double fy, int steps, int lower = 600, int upper = 200) {
  return {{"materials", {{"steel", {{"E", 2e11}, {"nu", 0.3}}}}},
          {"sections", {{"beam", {{"A", 4e-3}, {"I", 2e-5}, {"shear_area", 3.3e-3}}},
                        {"top", {{"A", 1e-3}, {"I", 1e-7}, {"shear_area", 8e-4}}}}},
          {"nodes", json::array({{{"id", 1}, {"x", 0.0}, {"y", 0.0}}, {{"id", 2}, {"x", 10.0}, {"y", 0.0}},
                                 {{"id", 3}, {"x", 0.005}, {"y", 0.06}}, {{"id", 4}, {"x", 9.995}, {"y", 0.06}}})},
          {"members", json::array({{{"from", 1}, {"to", 2}, {"divisions", lower}, {"material", "steel"}, {"section", "beam"}, {"element", "timoshenko"}},
                                   {{"from", 3}, {"to", 4}, {"divisions", upper}, {"material", "steel"}, {"section", "top"}, {"element", "timoshenko"},
                                    {"load", {{"fy", fy}}}}})},
          {"supports", json::array({{{"node", 1}, {"type", "pinned"}}, {{"node", 2}, {"type", "roller-x"}},
                                    {{"node", 3}, {"type", "pinned"}}, {{"node", 4}, {"type", "pinned"}}})},
          {"contacts", json::array({{{"nodes", {{"members", {1}}}}, {"members", {0}}, {"gap", 0.05}}})},
          {"analysis", {{"control", {{"type", "load"}, {"steps", steps}}}}}};
}

/// The pressed beams at length: the pinned upper beam (`length` m in 10-cm Timoshenko elements,
/// EI 2e4, every node a contact node) drawn 1 cm above a lower beam of three elements per upper
/// one (EI 4e6, pinned and on a roller at its ends) supported every 10 m, under fy (N/m) in
/// `steps` load steps — the continuous press of bench/contact_scale.py.
inline json continuous_press(int length, double fy, int steps) {
  const int upper = 10 * length;
  json m = pressed_beams(fy, steps, 3 * upper, upper);
  m["nodes"][1]["x"] = static_cast<double>(length);
  m["nodes"][3]["x"] = length - 0.005;
  for (int k = 1; k < length / 10; ++k)
    m["supports"].push_back({{"node", json::array({10.0 * k, 0.0})}, {"fix", json::array({"uy"})}});
  return m;
}

/// A load riding on a simply supported beam (10 m, 20 Timoshenko elements, EI 4e6): node 9
/// drawn at its contact's gap (5 cm) above x = 1, its ux prescribed by `ride` and its uy free,
/// pressed down by λ·10 kN, in `steps` load steps.
inline json riding_load(double ride, int steps) {
  return {{"materials", {{"steel", {{"E", 2e11}, {"G", 7.7e10}}}}},
          {"sections", {{"s", {{"A", 0.004}, {"I", 2e-5}, {"shear_area", 0.002}}}}},
          {"nodes", json::array({{{"id", 1}, {"x", 0.0}, {"y", 0.0}}, {{"id", 2}, {"x", 10.0}, {"y", 0.0}},
                                 {{"id", 9}, {"x", 1.0}, {"y", 0.05}}})},
          {"members", json::array({{{"from", 1}, {"to", 2}, {"divisions", 20}, {"element", "timoshenko"},
                                    {"material", "steel"}, {"section", "s"}}})},
          {"supports", json::array({{{"node", 1}, {"type", "pinned"}}, {{"node", 2}, {"type", "roller-x"}}})},
          {"loads", json::array({{{"node", 9}, {"fy", -1e4}}})},
          {"prescribed", json::array({{{"node", 9}, {"ux", ride}}})},
          {"contacts", json::array({{{"node", 9}, {"members", "all"}, {"gap", 0.05}}})},
          {"analysis", {{"control", {{"type", "load"}, {"steps", steps}}}}}};
}

/// The reader's reason for refusing `m` (file: path: reason), or "" if it accepts it.
inline std::string refusal(const json& m) {
  try {
    io::read_model(m);
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

/// Displacements (u, v, Θ) of a node id in a converged step.
inline Eigen::Vector3d node_displacement(const Model& model, const solver::StepRecord& step, int id) {
  return step.displacements.segment<3>(dofs_per_node * model.node_index(id));
}

/// Current position of a node.
inline Eigen::Vector2d node_position(const Model& model, const solver::StepRecord& step, int id) {
  const int k = model.node_index(id);
  return model.nodes[k].position + step.displacements.segment<2>(dofs_per_node * k);
}

}  // namespace tsm::test

#include <gtest/gtest.h>

namespace tsm::test {

/// Σ reactions + Σ λ F_ref = 0 for forces and for moments about the origin (current geometry),
/// relative to the largest force (× size, for moments) present.
inline void expect_global_equilibrium(const Model& model, const solver::StepRecord& step, double tolerance = 1e-9) {
  ASSERT_TRUE(step.has_state);
  Eigen::Vector3d total = Eigen::Vector3d::Zero();
  double force_scale = 0.0, moment_scale = 0.0;
  for (int k = 0; k < model.node_count(); ++k) {
    const Eigen::Vector3d f =
        step.reactions.segment<3>(3 * k) + step.load_factor * model.reference_load.segment<3>(3 * k);
    const Eigen::Vector2d x = model.nodes[k].position + step.displacements.segment<2>(3 * k);
    total += Eigen::Vector3d(f[0], f[1], f[2] + x.x() * f[1] - x.y() * f[0]);
    force_scale = std::max(force_scale, f.head<2>().norm());
    moment_scale = std::max({moment_scale, std::abs(f[2]), f.head<2>().norm() * x.norm()});
  }
  const double forces = std::max(force_scale, moment_scale / model.size);
  const double moments = std::max(moment_scale, force_scale * model.size);
  EXPECT_LE(std::abs(total[0]), tolerance * forces) << "step " << step.step;
  EXPECT_LE(std::abs(total[1]), tolerance * forces) << "step " << step.step;
  EXPECT_LE(std::abs(total[2]), tolerance * moments) << "step " << step.step;
}

}  // namespace tsm::test
