#include "tsmframe/io/model_drawing.hpp"

#include <algorithm>
#include <map>
#include <sstream>
#include <utility>
#include <vector>

#include "tsmframe/io/mesh_json.hpp"
#include "tsmframe/model/hinges.hpp"
#include "tsmframe/model/stage.hpp"

namespace tsm::io {
namespace {

/// Whether a dof is moved by a prescribed displacement of the model as read (a stage's are its own).
bool moved(const Model& model, int dof) { return model.prescribed(dof) != 0.0; }

/// "supports": per held node the dofs its supports hold — "ux", "uy", "rz", or at a skew roller
/// "n" (normal to its plane, `along` the plane). A hinge's rotation (held by the reader, since
/// no element holds it) and a prescribed dof that moves are no support.
void write_supports(JsonWriter& w, const Model& model) {
  const std::vector<char> hinge = hinge_nodes(model);
  std::vector<const SkewRoller*> skew(model.node_count(), nullptr);
  for (const SkewRoller& r : model.skew_rollers) skew[r.node] = &r;
  w.newline().key("supports").begin_array();
  for (int k = 0; k < model.node_count(); ++k) {
    const auto held = [&](int dof) {
      const int d = dofs_per_node * k + dof;
      return model.constrained[d] && !moved(model, d) && !(dof == rz && hinge[k]);
    };
    if (!held(ux) && !held(uy) && !held(rz)) continue;
    w.newline().begin_object().key("node").value(model.nodes[k].id).key("held").begin_array();
    if (skew[k]) {
      if (held(uy)) w.value("n");  // the roller's normal sits at the uy slot (model/nodal_frames.hpp)
    } else {
      if (held(ux)) w.value("ux");
      if (held(uy)) w.value("uy");
    }
    if (held(rz)) w.value("rz");
    w.end_array();
    if (skew[k]) w.key("along").begin_array().value(skew[k]->along.x()).value(skew[k]->along.y()).end_array();
    w.end_object();
  }
  w.end_array();
}

void write_springs(JsonWriter& w, const Model& model) {
  w.newline().key("springs").begin_array();
  for (const NodalSpring& s : model.springs) {
    w.newline().begin_object().key("node").value(model.nodes[s.node].id);
    w.key("kind").value(s.kind == NodalSpring::Kind::rotation ? "rotation" : "translation");
    if (s.kind == NodalSpring::Kind::translation)
      w.key("direction").begin_array().value(s.direction.x()).value(s.direction.y()).end_array();
    w.key("stiffness").value(s.stiffness).end_object();
  }
  w.end_array();
}

/// What one stage applies (the whole analysis without stages), per unit of its load factor.
struct LoadCase {
  std::string name;
  Eigen::VectorXd load;  ///< per dof, nodal, fixed in direction (empty: none)
  const std::vector<FollowerForce>* followers;
  bool pressures;  ///< the members' follower pressures (the first stage's)
  std::vector<PrescribedTarget> prescribed;
};

std::vector<LoadCase> load_cases(const Model& model) {
  if (model.stages.empty()) {
    LoadCase only{"", model.reference_load, &model.follower_forces, true, {}};
    for (int dof = 0; dof < model.dof_count(); ++dof)
      if (moved(model, dof)) only.prescribed.push_back({.dof = dof, .value = model.prescribed(dof)});
    return {only};
  }
  std::vector<LoadCase> cases;
  for (int t = 0; t < static_cast<int>(model.stages.size()); ++t) {
    const Stage& s = model.stages[t];
    cases.push_back({s.name, fixed_load(model, t), &s.follower_forces, t == 0, s.prescribed});
  }
  return cases;
}

void write_load_case(JsonWriter& w, const Model& model, const LoadCase& c) {
  w.newline().begin_object().key("name").value(c.name);
  w.key("loads").begin_array();  // [node, fx, fy, mz]
  for (int k = 0; k < model.node_count() && c.load.size() > 0; ++k) {
    const auto f = c.load.segment<3>(dofs_per_node * k);
    if (f.isZero(0.0)) continue;
    w.newline().begin_array().value(model.nodes[k].id).value(f[0]).value(f[1]).value(f[2]).end_array();
  }
  w.end_array().key("follower").begin_array();  // [node, fx, fy] as drawn
  for (const FollowerForce& f : *c.followers)
    w.newline().begin_array().value(model.nodes[f.node].id).value(f.force.x()).value(f.force.y()).end_array();
  w.end_array().key("pressures").begin_array();  // [member, pressure]
  for (int m = 0; c.pressures && m < static_cast<int>(model.member_extras.size()); ++m)
    if (model.member_extras[m].pressure != 0.0) w.begin_array().value(m).value(model.member_extras[m].pressure).end_array();
  w.end_array().key("prescribed").begin_array();  // {node, dof, value, increment}
  for (const PrescribedTarget& p : c.prescribed) {
    w.newline().begin_object().key("node").value(model.nodes[p.dof / dofs_per_node].id);
    w.key("dof").value(dof_name(p.dof % dofs_per_node)).key("value").value(p.value).key("increment").value(p.increment);
    w.end_object();
  }
  w.end_array().end_object();
}

/// "contacts": the contact nodes (ascending ids) grouped by the members they may touch and their gap.
void write_contacts(JsonWriter& w, const Model& model) {
  std::map<std::pair<std::vector<int>, double>, std::vector<int>> groups;
  std::vector<std::pair<std::vector<int>, double>> order;  // the groups as first met
  for (const ContactSpec& c : model.contacts) {
    auto key = std::make_pair(c.members, c.gap);
    auto [it, added] = groups.try_emplace(key);
    if (added) order.push_back(key);
    it->second.push_back(model.nodes[c.node].id);
  }
  w.newline().key("contacts").begin_array();
  for (const auto& key : order) {
    std::sort(groups[key].begin(), groups[key].end());  // a set of nodes, however the entries listed them
    w.newline().begin_object().key("nodes").begin_array();
    for (int id : groups[key]) w.value(id);
    w.end_array().key("members").begin_array();
    for (int m : key.first) w.value(m);
    w.end_array().key("gap").value(key.second).end_object();
  }
  w.end_array();
}

}  // namespace

void write_model_symbols(JsonWriter& w, const Model& model) {
  write_supports(w, model);
  write_springs(w, model);
  w.newline().key("load_cases").begin_array();
  for (const LoadCase& c : load_cases(model)) write_load_case(w, model, c);
  w.end_array();
  write_contacts(w, model);
}

void write_model_drawing(std::ostream& out, const Model& model, const std::optional<std::string>& mechanism) {
  JsonWriter w(out);
  w.begin_object().key("format").value("tsmframe-drawing/1").key("title").value(model.title);
  w.key("units").begin_object();
  for (const auto& [name, unit] : model.units) w.key(name).value(unit);
  w.end_object();
  if (mechanism) w.key("mechanism").value(*mechanism);
  write_mesh(w, model);
  write_model_symbols(w, model);
  w.end_object();
  out << '\n';
}

std::string model_drawing(const Model& model, const std::optional<std::string>& mechanism) {
  std::ostringstream out;
  write_model_drawing(out, model, mechanism);
  return out.str();
}

}  // namespace tsm::io
