#include "tsmframe/io/analysis_reader.hpp"

#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>

#include "tsmframe/io/json_input.hpp"

namespace tsm::io {
namespace {

using nlohmann::json;

constexpr long max_steps = 10'000'000;
constexpr double max_kept_state_bytes = 8e9;  // the converged states an output selection keeps (check_kept_states)

/// The steps whose state an output selection keeps on a path of known length (load and
/// displacement control: arc-length's max_steps is a bound, not a count, and counts nil).
double kept_steps(const Control& control, const OutputSelection& output) {
  if (control.type == ControlType::arc_length) return 0.0;
  const double legs = control.path.empty() ? 1.0 : static_cast<double>(control.path.size());  // from λ = 0 to each point
  const double steps = static_cast<double>(control.steps) * legs;
  return output.kind == OutputSelection::Kind::last ? 1.0
         : output.kind == OutputSelection::Kind::every ? std::ceil(steps / output.every) + 1.0
                                                        : steps;
}

void read_load_control(const json& c, const std::string& path, Control& control) {
  check_keys(c, path, {"type", "steps", "path"});
  control.type = ControlType::load;
  if (!c.contains("path")) return;
  const std::string ppath = child(path, "path");
  expect_array(c["path"], ppath);
  if (c["path"].empty() || c["path"].size() > 1000) fail(ppath, "give 1 to 1000 load factors to visit in turn");
  double previous = 0.0;
  for (size_t k = 0; k < c["path"].size(); ++k) {
    const double v = number(c["path"][k], child(ppath, k));
    if (v == previous) fail(child(ppath, k), "repeats the load factor before it (a leg must move)");
    control.path.push_back(previous = v);
  }
}

void read_displacement_control(const json& c, const std::string& path, const ControlContext& at, Control& control) {
  const Model& model = at.model;
  const NodeResolver& node = at.node;
  check_keys(c, path, {"type", "steps", "node", "dof", "target"});
  control.type = ControlType::displacement;
  if (!c.contains("node")) fail(child(path, "node"), "missing (required)");
  control.node = node(c["node"], child(path, "node"));
  if (!c.contains("dof")) fail(child(path, "dof"), "missing (required)");
  control.dof = dof_from_name(string(c["dof"], child(path, "dof")), child(path, "dof"));
  control.target = required_number(c, "target", path);
  if (control.target == 0.0 && at.at_rest) fail(child(path, "target"), "must not be zero");
  if (at.constrained[dofs_per_node * control.node + control.dof])
    fail(child(path, "dof"), std::string("the controlled dof ") + dof_name(control.dof) + " of node " +
                                 std::to_string(model.nodes[control.node].id) + " is fixed or prescribed");
}

/// Arc-length's "until": a load factor, or a value of one free dof, where the path stops.
void read_until(const json& u, const std::string& upath, const ControlContext& at, Control& control) {
  const Model& model = at.model;
  const NodeResolver& node = at.node;
  expect_object(u, upath);
  if (u.contains("load_factor")) {
    check_keys(u, upath, {"load_factor"});
    control.until = Control::Until::load_factor;
    control.until_value = required_number(u, "load_factor", upath);
    if (control.until_value == 0.0) fail(child(upath, "load_factor"), "must not be zero (the path starts there)");
    return;
  }
  check_keys(u, upath, {"node", "dof", "value"});
  control.until = Control::Until::displacement;
  if (!u.contains("node")) fail(child(upath, "node"), "missing (required)");
  control.until_node = node(u["node"], child(upath, "node"));
  if (!u.contains("dof")) fail(child(upath, "dof"), "missing (required, or give \"load_factor\")");
  control.until_dof = dof_from_name(string(u["dof"], child(upath, "dof")), child(upath, "dof"));
  control.until_value = required_number(u, "value", upath);
  if (at.constrained[dofs_per_node * control.until_node + control.until_dof])
    fail(child(upath, "dof"), std::string("the dof ") + dof_name(control.until_dof) + " of node " +
                                  std::to_string(model.nodes[control.until_node].id) + " is fixed or prescribed");
  if (control.until_value == 0.0) fail(child(upath, "value"), "must not be zero (the path starts there)");
}

void read_arc_length_control(const json& c, const std::string& path, const ControlContext& at, Control& control) {
  check_keys(c, path, {"type", "initial_increment", "max_steps", "until", "min_increment", "max_increment"});
  control.type = ControlType::arc_length;
  control.initial_increment = positive(required_number(c, "initial_increment", path), child(path, "initial_increment"));
  if (!c.contains("max_steps")) fail(child(path, "max_steps"), "missing (required)");
  control.max_steps = static_cast<int>(bounded_integer(c["max_steps"], child(path, "max_steps"), 1, max_steps));
  control.min_increment = control.initial_increment / 1024.0;
  control.max_increment = 10.0 * control.initial_increment;
  if (auto v = optional_number(c, "min_increment", path)) control.min_increment = positive(*v, child(path, "min_increment"));
  if (auto v = optional_number(c, "max_increment", path)) control.max_increment = positive(*v, child(path, "max_increment"));
  if (control.min_increment > control.initial_increment) fail(child(path, "min_increment"), "must not exceed initial_increment");
  if (control.max_increment < control.initial_increment) fail(child(path, "max_increment"), "must not be below initial_increment");
  if (c.contains("until")) read_until(c["until"], child(path, "until"), at, control);
}

}  // namespace

void read_control(const json& c, const std::string& path, const ControlContext& at, Control& control) {
  expect_object(c, path);
  if (!c.contains("type")) fail(child(path, "type"), "missing (required: \"load\", \"displacement\" or \"arc-length\")");
  const std::string type = string(c["type"], child(path, "type"));
  if (type == "load") read_load_control(c, path, control);
  else if (type == "displacement") read_displacement_control(c, path, at, control);
  else if (type == "arc-length") read_arc_length_control(c, path, at, control);
  else fail(child(path, "type"), "unknown control " + quote_text(type) + " (expected \"load\", \"displacement\" or \"arc-length\")");
  if (c.contains("steps")) control.steps = static_cast<int>(bounded_integer(c["steps"], child(path, "steps"), 1, max_steps));
}

void read_output(const json& o, const std::string& path, OutputSelection& out) {
  if (o.is_string()) {
    const std::string kind = o.get<std::string>();
    if (kind == "all") out.kind = OutputSelection::Kind::all;
    else if (kind == "last") out.kind = OutputSelection::Kind::last;
    else fail(path, "expected \"all\", \"last\" or a whole number k (every k-th step)");
    return;
  }
  if (!o.is_number()) fail(path, "expected \"all\", \"last\" or a whole number k (every k-th step)");
  out.kind = OutputSelection::Kind::every;
  out.every = static_cast<int>(bounded_integer(o, path, 1, max_steps));
}

/// Where buckling is estimated: "unloaded", "end" (the last converged state) or a step number.
void read_buckling_at(const json& at, const std::string& path, AnalysisSettings& a) {
  const std::string expected = "expected \"unloaded\", \"end\" or a step number";
  if (at.is_number()) {
    a.buckling_at = AnalysisSettings::BucklingAt::step;
    a.buckling_step = static_cast<int>(bounded_integer(at, path, 1, max_steps));
    return;
  }
  if (!at.is_string()) fail(path, expected);
  const std::string where = at.get<std::string>();
  if (where == "end") a.buckling_at = AnalysisSettings::BucklingAt::end;
  else if (where != "unloaded") fail(path, expected + ", got " + quote_text(where));
}

void read_analysis_settings(const json& an, Model& model, const NodeResolver& node) {
  AnalysisSettings& a = model.analysis;
  expect_object(an, "analysis");
  check_keys(an, "analysis", {"control", "tolerance", "max_iterations", "cutback", "max_cutbacks", "output", "monitor", "buckling"});
  if (an.contains("control")) read_control(an["control"], "analysis.control", {model, model.constrained, node}, a.control);
  if (auto tol = optional_number(an, "tolerance", "analysis")) {
    if (!(*tol > 0.0 && *tol < 1.0)) fail("analysis.tolerance", "must lie between 0 and 1");
    a.tolerance = *tol;
  }
  if (an.contains("max_iterations"))
    a.max_iterations = static_cast<int>(bounded_integer(an["max_iterations"], "analysis.max_iterations", 1, 100000));
  if (an.contains("cutback")) a.cutback = boolean(an["cutback"], "analysis.cutback");
  if (an.contains("max_cutbacks"))
    a.max_cutbacks = static_cast<int>(bounded_integer(an["max_cutbacks"], "analysis.max_cutbacks", 0, 60));
  if (an.contains("output")) read_output(an["output"], "analysis.output", a.output);
  if (an.contains("buckling")) {
    const json& b = an["buckling"];
    expect_object(b, "analysis.buckling");
    check_keys(b, "analysis.buckling", {"modes", "at"});
    a.buckling_modes = b.contains("modes") ? static_cast<int>(bounded_integer(b["modes"], "analysis.buckling.modes", 1, 50)) : 3;
    if (b.contains("at")) read_buckling_at(b["at"], "analysis.buckling.at", a);
  }
  if (an.contains("monitor")) {
    expect_array(an["monitor"], "analysis.monitor");
    for (size_t k = 0; k < an["monitor"].size(); ++k) a.monitor.push_back(node(an["monitor"][k], child("analysis.monitor", k)));
  }
}

/// The steps whose full state the output selection keeps (in memory until the run ends, then in
/// results.json) must fit: a step count meant as 100 and typed as 100,000 on a large model would
/// otherwise run for hours and then run out of memory. Load and displacement control only, whose
/// step count is known (arc-length's max_steps is a bound, not a count).
void check_kept_states(const Model& model) {
  double kept = 0.0;
  if (model.stages.empty()) kept = kept_steps(model.analysis.control, model.analysis.output);
  for (const Stage& stage : model.stages) kept += kept_steps(stage.control, stage.output);
  // Per kept step: displacements and reactions (3 per node), element forces (4 per element), 8 bytes each.
  const double bytes = kept * 8.0 * (6.0 * model.node_count() + 4.0 * static_cast<double>(model.elements.size()));
  if (bytes <= max_kept_state_bytes) return;
  std::ostringstream os;
  os.precision(3);
  os << "keeping the full state of " << static_cast<long long>(kept) << " steps of " << model.elements.size()
     << " elements takes ~" << bytes / 1e9 << " GB of memory, and more in results.json (at most "
     << max_kept_state_bytes / 1e9 << " GB): give \"output\" a step interval k (every k-th step) or \"last\", or fewer steps";
  fail(model.stages.empty() ? "analysis.output" : "stages", os.str());
}

}  // namespace tsm::io
