#include "tsmframe/io/restart_reader.hpp"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "tsmframe/io/friction_names.hpp"
#include "tsmframe/io/input_error.hpp"
#include "tsmframe/io/input_file.hpp"
#include "tsmframe/io/json_input.hpp"
#include "tsmframe/model/nodal_frames.hpp"

namespace tsm::io {
namespace {

using nlohmann::json;

/// The results come from a run of this model: its nodes (ids, as drawn), elements (ids, ends)
/// and contacts, one for one.
void check_same_model(const json& results, const Model& model) {
  const json& nodes = results.at("nodes");
  expect_array(nodes, "nodes");
  const std::string other = "results of another model: ";
  if (nodes.size() != static_cast<size_t>(model.node_count()))
    fail("nodes", other + std::to_string(nodes.size()) + " nodes there, " + std::to_string(model.node_count()) + " here");
  for (size_t k = 0; k < nodes.size(); ++k) {
    const std::string path = child("nodes", k);
    expect_object(nodes[k], path);
    const Node& node = model.nodes[k];
    const Eigen::Vector2d there(required_number(nodes[k], "x", path), required_number(nodes[k], "y", path));
    if (integer(nodes[k].at("id"), child(path, "id")) != node.id || (there - node.position).norm() > 1e-12 * model.size)
      fail(path, other + "node " + std::to_string(node.id) + " is not the same node here");
  }
  const json& elements = results.at("elements");
  expect_array(elements, "elements");
  if (elements.size() != model.elements.size())
    fail("elements", other + std::to_string(elements.size()) + " elements there, " + std::to_string(model.elements.size()) + " here");
  for (size_t k = 0; k < elements.size(); ++k) {
    const std::string path = child("elements", k);
    const Element& e = model.elements[k];
    const json& ends = elements[k].at("nodes");
    if (integer(elements[k].at("id"), child(path, "id")) != e.id || integer(ends.at(0), path) != model.nodes[e.start].id ||
        integer(ends.at(1), path) != model.nodes[e.end].id)
      fail(path, other + "element " + std::to_string(e.id) + " is not the same element here");
  }
}

/// The kept step: number `step`, or the newest with state (0).
const json& kept_step(const json& steps, int step, std::string& path) {
  expect_array(steps, "steps");
  for (size_t k = steps.size(); k-- > 0;) {
    const json& s = steps[k];
    if (!s.is_object() || !s.contains("step")) continue;
    const bool has_state = s.contains("state") && s.value("converged", false);
    if (step == 0 && !has_state) continue;
    if (step != 0 && integer(s["step"], child(child("steps", k), "step")) != step) continue;
    path = child("steps", k);
    if (!has_state)
      fail(path, "step " + std::to_string(step) +
                     " carries no state (not converged, or not kept by the run's analysis.output): restart from a step "
                     "with state, or keep every step (\"output\": \"all\")");
    return s;
  }
  if (step == 0) fail("steps", "no converged step with state to restart from");
  fail("steps", "no step " + std::to_string(step) + " in these results");
}

/// Per node id, [ux, uy, rz] (results.json's displacements) into all dofs.
Eigen::VectorXd read_triples(const json& triples, const std::string& path, const Model& model) {
  Eigen::VectorXd values = Eigen::VectorXd::Zero(model.dof_count());
  for (int k = 0; k < model.node_count(); ++k) {
    const std::string id = std::to_string(model.nodes[k].id), at = child(path, id);
    const json& d = triples.at(id);
    if (!d.is_array() || d.size() != 3) fail(at, "expected [ux, uy, rz]");
    for (int dof = 0; dof < dofs_per_node; ++dof) values[dofs_per_node * k + dof] = number(d[dof], child(at, dof));
  }
  return values;
}

/// Arc-length control's memory at the kept step: it goes on as the whole run did. The step must
/// have been taken under arc-length control if the model's control (its stage's) is one.
void read_arc_length(const json& state, const std::string& path, const Model& model, int stage, solver::State& out) {
  const Control& control = model.stages.empty() ? model.analysis.control : model.stages[stage].control;
  if ((control.type == ControlType::arc_length) != state.contains("arc_length"))
    fail(child(path, "arc_length"), control.type == ControlType::arc_length
                                        ? "the step was not taken under arc-length control, which the model's is"
                                        : "the step was taken under arc-length control, which the model's is not");
  if (!state.contains("arc_length")) return;
  const json& arc = state["arc_length"];
  const std::string at = child(path, "arc_length");
  out.arc_length.next_arc = positive(required_number(arc, "next_arc", at), child(at, "next_arc"));
  out.arc_length.converged_steps = static_cast<int>(bounded_integer(arc.at("steps"), child(at, "steps"), 0, 2'000'000'000L));
  out.arc_length.previous_load_increment = required_number(arc, "previous_load_increment", at);
  if (arc.contains("previous_increment"))
    out.arc_length.previous_increment = read_triples(arc["previous_increment"], child(at, "previous_increment"), model);
}

/// A frictional contact's history: its anchor on its member and the slip so far. A state written
/// without it (a run without friction) cannot tell where the contact sticks: refused.
void read_friction(const json& c, const std::string& at, const Model& model, contact::FrictionState& f) {
  if (!c.contains("friction"))
    fail(at, "no friction history here, and this model's contact has friction: restart from a run with the same friction");
  const json& h = c["friction"];
  const std::string fat = child(at, "friction");
  f.anchored = boolean(h.at("anchored"), child(fat, "anchored"));
  f.slip = required_number(h, "slip", fat);
  f.step_tangential = required_number(h, "tangential", fat);
  const std::string status = string(h.at("status"), child(fat, "status"));
  const auto named = std::find(friction_names.begin(), friction_names.end(), status);
  if (named == friction_names.end()) fail(child(fat, "status"), "unknown friction status " + quote_text(status));
  f.status = f.step_status = static_cast<contact::FrictionStatus>(named - friction_names.begin());
  if (!f.anchored) return;
  f.member = static_cast<int>(bounded_integer(h.at("member"), child(fat, "member"), 0, model.member_count - 1));
  f.anchor = required_number(h, "anchor", fat);
}

/// Each contact's state at the kept step (element ids made indices).
void read_contacts(const json& contacts, const std::string& path, const Model& model, solver::State& state) {
  expect_array(contacts, path);
  if (contacts.size() != model.contacts.size())
    fail(path, "results of another model: " + std::to_string(contacts.size()) + " contacts there, " +
                   std::to_string(model.contacts.size()) + " here");
  const auto element_index = [&](const json& id, const std::string& at) {
    const long e = integer(id, at) - 1;  // ids are 1-based in generation order
    if (e < 0 || e >= static_cast<long>(model.elements.size())) fail(at, "no such element");
    return static_cast<int>(e);
  };
  state.contacts.resize(contacts.size());
  for (size_t k = 0; k < contacts.size(); ++k) {
    const std::string at = child(path, k);
    const json& c = contacts[k];
    contact::ContactState& s = state.contacts[k];
    s.active = boolean(c.at("active"), child(at, "active"));
    if (!s.active) continue;
    s.element = element_index(c.at("element"), child(at, "element"));
    s.side = static_cast<int>(bounded_integer(c.at("side"), child(at, "side"), -1, 1));
    s.alpha = required_number(c, "alpha", at);
    s.force = required_number(c, "force", at);
    s.Y = required_number(c, "Y", at);
    s.entering = boolean(c.at("entering"), child(at, "entering"));
    const Eigen::Vector2d push = point(c.at("push"), child(at, "push"));
    s.push[0] = push.x();
    s.push[1] = push.y();
    if (c.contains("vertex")) {
      const json& v = c["vertex"];
      const std::string vat = child(at, "vertex");
      s.vertex = contact::Vertex{element_index(v.at("element"), child(vat, "element")),
                                 static_cast<int>(bounded_integer(v.at("side"), child(vat, "side"), -1, 1)),
                                 required_number(v, "Y", vat)};
    }
    if (model.contacts[k].friction > 0.0) read_friction(c, at, model, s.friction);
  }
}

}  // namespace

solver::RestartPoint read_restart(const json& results, int step, const Model& model) {
  try {
    expect_object(results, "(document)");
    if (results.value("format", "") != "tsmframe-results/1") fail("format", "not a tsmframe results file (tsmframe-results/1)");
    check_same_model(results, model);
    std::string path;
    const json& s = kept_step(results.at("steps"), step, path);
    solver::RestartPoint point;
    point.step = static_cast<int>(integer(s.at("step"), child(path, "step")));
    if (model.stages.empty() == s.contains("stage"))
      fail(path, model.stages.empty() ? "results of a staged run; this model has no stages" : "results of a run without stages; this model has stages");
    if (s.contains("stage"))
      point.stage = static_cast<int>(bounded_integer(s["stage"], child(path, "stage"), 1, static_cast<long>(model.stages.size()))) - 1;
    const std::string spath = child(path, "state");
    const json& state = s.at("state");
    point.state.load_factor = required_number(s, "load_factor", path);
    point.state.path_parameter = required_number(state, "path_parameter", spath);
    point.state.displacements = read_triples(s.at("displacements"), child(path, "displacements"), model);
    NodalFrames(model).to_nodal(point.state.displacements);  // the state's frames at skew rollers
    read_arc_length(state, spath, model, point.stage, point.state);
    const json& rotations = state.at("chord_rotations");
    if (!rotations.is_array() || rotations.size() != model.elements.size())
      fail(child(spath, "chord_rotations"), "expected one chord rotation per element");
    for (size_t e = 0; e < rotations.size(); ++e) point.state.chord_rotations.push_back(number(rotations[e], child(child(spath, "chord_rotations"), e)));
    read_contacts(state.at("contacts"), child(spath, "contacts"), model, point.state);
    if (state.contains("stage_load_factors"))
      for (size_t k = 0; k < state["stage_load_factors"].size(); ++k)
        point.final_load_factors.push_back(number(state["stage_load_factors"][k], child(child(spath, "stage_load_factors"), k)));
    if (point.final_load_factors.size() != static_cast<size_t>(point.stage))
      fail(child(spath, "stage_load_factors"), "expected the load factor each earlier stage ended at");
    if (state.contains("stage_start"))
      for (size_t k = 0; k < state["stage_start"].size(); ++k) {
        const json& entry = state["stage_start"][k];
        const std::string at = child(child(spath, "stage_start"), k);
        const long id = integer(entry.at(0), at);
        const int node = model.node_index(static_cast<int>(id));
        if (node < 0) fail(at, "no node " + std::to_string(id));
        point.stage_start.emplace_back(dofs_per_node * node + dof_from_name(string(entry.at(1), at), at), number(entry.at(2), at));
      }
    return point;
  } catch (const json::exception& e) {  // a key missing or of the wrong kind where .at() looked
    fail("(document)", std::string("not a results file a run can go on from: ") + e.what());
  }
}

solver::RestartPoint read_restart_file(const std::string& where, const Model& model) {
  const size_t hash = where.rfind('#');
  const std::string path = hash == std::string::npos ? where : where.substr(0, hash);
  int step = 0;
  if (hash != std::string::npos) {
    const std::string number = where.substr(hash + 1);
    char* end = nullptr;
    const long n = std::strtol(number.c_str(), &end, 10);
    if (number.empty() || *end != '\0' || n < 1 || n > 2'000'000'000L)
      throw InputError("", "#" + number + ": expected a step number (1, 2, …) after '#'");
    step = static_cast<int>(n);
  }
  return read_restart(parse_json(read_input_file(path, "the results file")), step, model);
}

}  // namespace tsm::io
