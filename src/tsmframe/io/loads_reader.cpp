#include "tsmframe/io/loads_reader.hpp"

#include <algorithm>
#include <nlohmann/json.hpp>

#include "tsmframe/io/input_error.hpp"
#include "tsmframe/io/json_input.hpp"
#include "tsmframe/model/hinges.hpp"

namespace tsm::io {

using nlohmann::json;

void LoadsReader::read_loads(const json& loads, const std::string& lpath, Eigen::VectorXd& load,
                             std::vector<FollowerForce>& followers) {
  expect_array(loads, lpath);
  if (hinge_.empty()) hinge_ = hinge_nodes(model_);
  for (size_t k = 0; k < loads.size(); ++k) {
    const std::string path = child(lpath, k);
    const json& l = loads[k];
    expect_object(l, path);
    check_keys(l, path, {"node", "member", "at", "fx", "fy", "mz", "follower"});
    const int node = load_node(l, path);
    const bool follower = l.contains("follower") && boolean(l["follower"], child(path, "follower"));
    const char* keys[3] = {"fx", "fy", "mz"};
    Eigen::Vector3d value = Eigen::Vector3d::Zero();
    for (int dof = 0; dof < dofs_per_node; ++dof)
      if (auto v = optional_number(l, keys[dof], path)) value[dof] = *v;
    if (value[rz] != 0.0 && hinge_[node] && !model_.constrained[dofs_per_node * node + rz])
      fail(child(path, "mz"), "node " + std::to_string(model_.nodes[node].id) +
                                  " is a hinge: every element end there is released, so it carries no moment");
    if (follower) followers.push_back(follower_force(path, node, value.head<2>()));
    else load.segment<2>(dofs_per_node * node) += value.head<2>();
    load[dofs_per_node * node + rz] += value[rz];  // a moment turns with nothing
    if ((value.array() != 0.0).any()) loaded_.insert(node);
  }
}

/// A load's node: given ("node"), or a member's station ("member", "at": member_stations).
int LoadsReader::load_node(const json& l, const std::string& path) const {
  if (l.contains("node") && (l.contains("member") || l.contains("at"))) fail(path, "give \"node\", or \"member\" and \"at\", not both");
  if (l.contains("node")) return node_(l["node"], child(path, "node"));
  if (!l.contains("member") && !l.contains("at")) fail(child(path, "node"), "missing (required, or give \"member\" and \"at\")");
  const int node = station_(static_cast<int>(integer(l.at("member"), child(path, "member"))), number(l.at("at"), child(path, "at")));
  if (node < 0) fail(path, "no node at that station");  // member_stations made one for every entry it read
  return node;
}

/// A force that turns with its node ("follower": true): it needs a node an element end turns
/// with, else its direction would follow a rotation that means nothing.
FollowerForce LoadsReader::follower_force(const std::string& path, int node, const Eigen::Vector2d& force) {
  if (force.x() == 0.0 && force.y() == 0.0) fail(path, "a follower load needs a force (fx or fy) to turn");
  if (turned_.empty()) turned_ = turned_nodes(model_);
  if (!turned_[node])
    fail(child(path, "follower"), "node " + std::to_string(model_.nodes[node].id) +
                                      " turns with no element end (a hinge, or held by no element): a follower "
                                      "load there has no rotation to follow");
  return {node, force};
}

std::vector<PrescribedTarget> LoadsReader::read_prescribed(const json& prescribed, const std::string& ppath, bool increments) {
  expect_array(prescribed, ppath);
  std::vector<PrescribedTarget> targets;
  std::set<int> seen;
  for (size_t k = 0; k < prescribed.size(); ++k) {
    const std::string path = child(ppath, k);
    const json& p = prescribed[k];
    expect_object(p, path);
    if (increments) check_keys(p, path, {"node", "ux", "uy", "rz", "increment"});
    else check_keys(p, path, {"node", "ux", "uy", "rz"});
    if (!p.contains("node")) fail(child(path, "node"), "missing (required)");
    const int node = node_(p["node"], child(path, "node"));
    const bool increment = p.contains("increment") && boolean(p["increment"], child(path, "increment"));
    const char* keys[3] = {"ux", "uy", "rz"};
    bool any = false;
    for (int dof = 0; dof < dofs_per_node; ++dof) {
      auto value = optional_number(p, keys[dof], path);
      if (!value) continue;
      any = true;
      const int g = dofs_per_node * node + dof;
      if (!seen.insert(g).second) fail(child(path, keys[dof]), std::string("this dof is already prescribed by an earlier entry"));
      targets.push_back({g, *value, increment});
      prescribed_.insert(node);
    }
    if (!any) fail(path, "give at least one of ux, uy, rz");
  }
  return targets;
}

namespace {

/// A stage's "contacts": the entries of the model's "contacts" that exist in it (indices), the
/// others off.
std::vector<char> contacts_off(const json& named, const std::string& path, const std::vector<int>& entries) {
  expect_array(named, path);
  const long count = static_cast<long>(entries.size()) - 1;
  std::vector<char> off(entries.back(), 1);
  for (size_t k = 0; k < named.size(); ++k) {
    const long entry = integer(named[k], child(path, k));
    if (entry < 0 || entry >= count)
      fail(child(path, k), "no contacts entry " + std::to_string(entry) + " (the model's \"contacts\" has " +
                                std::to_string(count) + (count == 1 ? " entry" : " entries") + ", numbered from 0)");
    std::fill(off.begin() + entries[entry], off.begin() + entries[entry + 1], 0);
  }
  return off;
}

}  // namespace

std::vector<Stage> LoadsReader::read_stages(const json& stages, const OutputSelection& output,
                                            const std::vector<int>& contact_entries) {
  expect_array(stages, "stages");
  if (stages.empty() || stages.size() > 1000) fail("stages", "give 1 to 1000 stages");
  std::vector<Stage> read;
  std::vector<bool> constrained = model_.constrained;  // the supports, then each stage's prescribed dofs
  for (size_t k = 0; k < stages.size(); ++k) {
    const std::string path = child("stages", k);
    const json& st = stages[k];
    expect_object(st, path);
    check_keys(st, path, {"name", "loads", "prescribed", "contacts", "control", "output"});
    Stage stage;
    if (st.contains("name")) stage.name = string(st["name"], child(path, "name"));
    stage.load = Eigen::VectorXd::Zero(model_.dof_count());
    if (st.contains("loads")) read_loads(st["loads"], child(path, "loads"), stage.load, stage.follower_forces);
    if (!stage.load.any()) stage.load.resize(0);
    if (st.contains("prescribed")) stage.prescribed = read_prescribed(st["prescribed"], child(path, "prescribed"), true);
    for (const PrescribedTarget& p : stage.prescribed) constrained[p.dof] = true;
    if (st.contains("contacts")) stage.contact_off = contacts_off(st["contacts"], child(path, "contacts"), contact_entries);
    if (st.contains("control")) read_control(st["control"], child(path, "control"), {model_, constrained, node_, k == 0}, stage.control);
    stage.output = output;
    if (st.contains("output")) read_output(st["output"], child(path, "output"), stage.output);
    read.push_back(std::move(stage));
  }
  return read;
}

namespace {

/// One loads array's stations into `stations`.
void add_stations(const json& loads, const std::string& lpath, std::vector<std::vector<double>>& stations) {
  if (!loads.is_array()) return;
  for (size_t k = 0; k < loads.size(); ++k) {
    const json& l = loads[k];
    if (!l.is_object() || (!l.contains("member") && !l.contains("at"))) continue;
    const std::string path = child(lpath, k);
    if (!l.contains("member")) fail(child(path, "member"), "missing (a load at \"at\" names its member)");
    if (!l.contains("at")) fail(child(path, "at"), "missing (where along the member, a fraction of its length: 0 < at < 1)");
    const long member = integer(l["member"], child(path, "member"));
    if (member < 0 || member >= static_cast<long>(stations.size()))
      fail(child(path, "member"), "unknown member " + std::to_string(member) + " (members are numbered 0 to " +
                                      std::to_string(static_cast<long>(stations.size()) - 1) + " in file order)");
    const double at = number(l["at"], child(path, "at"));
    if (!(at > 0.0 && at < 1.0)) fail(child(path, "at"), "must lie between 0 and 1 (a fraction of the member's length from its \"from\" node)");
    stations[member].push_back(at);
  }
}

}  // namespace

std::vector<std::vector<double>> member_stations(const json& document, size_t members) {
  std::vector<std::vector<double>> stations(members);
  if (document.contains("loads")) add_stations(document["loads"], "loads", stations);
  if (document.contains("stages") && document["stages"].is_array())
    for (size_t s = 0; s < document["stages"].size(); ++s)
      if (document["stages"][s].is_object() && document["stages"][s].contains("loads"))
        add_stations(document["stages"][s]["loads"], child(child("stages", s), "loads"), stations);
  for (std::vector<double>& list : stations) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  return stations;
}

void refuse_unstaged_keys(const json& document) {
  for (const char* key : {"loads", "prescribed"})
    if (document.contains(key))
      fail(key, std::string("with \"stages\", give the ") + key + " in the stage that applies them (stages[k]." + key + ")");
  if (document.contains("analysis") && document["analysis"].is_object() && document["analysis"].contains("control"))
    fail("analysis.control", "with \"stages\", each stage has its own control (stages[k].control)");
}

}  // namespace tsm::io
