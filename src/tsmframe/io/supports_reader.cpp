#include "tsmframe/io/supports_reader.hpp"

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tsmframe/io/json_input.hpp"

namespace tsm::io {
namespace {

using json = nlohmann::json;

/// A "roller" direction: the node rolls along it. Along x or y it is a plain roller (uy or ux
/// held, `fixed`); otherwise a skew roller (true).
bool read_roller(const json& value, const std::string& path, int node, std::set<int>& fixed, Model& model) {
  const Eigen::Vector2d along = point(value, path);
  if (!(along.norm() > 0.0)) fail(path, "the direction the node rolls along must not be [0, 0]");
  if (along.y() == 0.0) fixed.insert(uy);
  else if (along.x() == 0.0) fixed.insert(ux);
  else model.skew_rollers.push_back({node, along.normalized()});
  return along.x() != 0.0 && along.y() != 0.0;
}

/// Whether a control's (or its until's) translation is at `node`.
bool controls_translation(const Control& c, int node) {
  return (c.type == ControlType::displacement && c.node == node && c.dof != rz) ||
         (c.until_node == node && c.until_dof != rz);
}

}  // namespace

std::vector<std::string> read_supports(const json& document, const NodeResolver& node_of, Model& model) {
  std::vector<std::string> roller_paths;
  for_each_entry(document, "supports", {"node", "fix", "type", "roller"}, [&](const json& s, const std::string& path) {
    if (!s.contains("node")) fail(child(path, "node"), "missing (required)");
    const int node = node_of(s["node"], child(path, "node"));
    if (!s.contains("fix") && !s.contains("type") && !s.contains("roller"))
      fail(path, "give \"fix\" (a list of ux, uy, rz), \"type\" or \"roller\"");
    std::set<int> fixed;
    if (s.contains("fix")) {
      expect_array(s["fix"], child(path, "fix"));
      for (size_t d = 0; d < s["fix"].size(); ++d) {
        const std::string dpath = child(child(path, "fix"), d);
        fixed.insert(dof_from_name(string(s["fix"][d], dpath), dpath));
      }
    }
    if (s.contains("type")) {
      const std::string type = string(s["type"], child(path, "type"));
      if (type == "fixed") fixed.insert({ux, uy, rz});
      else if (type == "pinned") fixed.insert({ux, uy});
      else if (type == "roller-x") fixed.insert(uy);
      else if (type == "roller-y") fixed.insert(ux);
      else fail(child(path, "type"), "unknown support type " + quote_text(type) + " (expected fixed, pinned, roller-x or roller-y)");
    }
    if (s.contains("roller")) {
      if (fixed.count(ux) || fixed.count(uy))
        fail(child(path, "roller"), "a roller holds the translation across its direction only: give \"fix\" no ux or uy, and no \"type\", with it");
      if (read_roller(s["roller"], child(path, "roller"), node, fixed, model)) roller_paths.push_back(child(path, "roller"));
    }
    for (int dof : fixed) model.constrained[dofs_per_node * node + dof] = true;
  });
  for (const SkewRoller& r : model.skew_rollers) model.constrained[dofs_per_node * r.node + uy] = true;  // n, in its frame
  return roller_paths;
}

void check_skew_rollers(const Model& model, const std::vector<std::string>& roller_paths, const std::set<int>& prescribed_nodes) {
  std::vector<int> skew(model.node_count(), 0);
  for (const SkewRoller& r : model.skew_rollers) ++skew[r.node];
  for (size_t k = 0; k < model.skew_rollers.size(); ++k) {
    const int node = model.skew_rollers[k].node;
    const auto refuse = [&](const std::string& what) {
      fail(roller_paths[k], "node " + std::to_string(model.nodes[node].id) + " " + what +
                                ": a skew roller's node moves along its plane, solved for in the plane's frame");
    };
    if (skew[node] > 1) refuse("has two skew rollers");
    if (model.constrained[dofs_per_node * node + ux]) refuse("has its translations held by another support too");
    if (prescribed_nodes.count(node)) refuse("has a prescribed displacement");
    if (controls_translation(model.analysis.control, node)) refuse("has its translation controlled or watched by the analysis");
    for (const Stage& stage : model.stages)
      if (controls_translation(stage.control, node)) refuse("has its translation controlled or watched by stage \"" + stage.name + "\"");
  }
}

}  // namespace tsm::io
