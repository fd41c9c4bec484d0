#include "tsmframe/io/model_reader.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>
#include <optional>
#include <set>
#include <unordered_map>

#include "tsmframe/io/analysis_reader.hpp"
#include "tsmframe/io/contact_options.hpp"
#include "tsmframe/io/input_error.hpp"
#include "tsmframe/io/input_file.hpp"
#include "tsmframe/io/json_input.hpp"
#include "tsmframe/io/loads_reader.hpp"
#include "tsmframe/io/member_options.hpp"
#include "tsmframe/io/section_table.hpp"
#include "tsmframe/io/supports_reader.hpp"
#include "tsmframe/io/system_error.hpp"
#include "tsmframe/model/hinges.hpp"
#include "tsmframe/model/mechanism.hpp"
#include "tsmframe/model/memory_estimate.hpp"
#include "tsmframe/model/mesh.hpp"
#include "tsmframe/model/resting_contact.hpp"

namespace tsm::io {
namespace {

using nlohmann::json;

constexpr long max_divisions = 10'000'000;        // per member: a typo must not exhaust memory
constexpr long max_elements = 20'000'000;         // per model

/// Where a member's value that meshing refused is written.
std::string mesh_error_path(const std::string& member_path, MeshError::Value value) {
  switch (value) {
    case MeshError::Value::member: return member_path;
    case MeshError::Value::arc: return child(member_path, "arc");
    case MeshError::Value::arc_centre: return child(child(member_path, "arc"), "center");
    case MeshError::Value::arc_sweep: return child(child(member_path, "arc"), "sweep");
  }
  return member_path;
}

/// Where in a model most of an estimate's memory goes: the members (elements), the contacts,
/// the output selection (kept states) or the control (steps).
std::string largest_part_path(const MemoryEstimate& e) {
  const std::pair<double, const char*> parts[] = {{e.elements.bytes, "members"},
                                                  {e.contacts.bytes, "contacts"},
                                                  {e.kept_states.bytes, "analysis.output"},
                                                  {e.steps.bytes, "analysis.control.steps"}};
  return std::max_element(std::begin(parts), std::end(parts))->second;
}

class Reader {
 public:
  /// `input_bytes`: the text `document` was parsed from (0: given in memory).
  Reader(const json& document, const MemoryBudget& budget, double input_bytes, Mechanisms mechanisms)
      : doc_(document), budget_(budget), input_bytes_(input_bytes), mechanisms_(mechanisms) {}

  Model read() {
    expect_object(doc_, "(document)");
    check_keys(doc_, "", {"$schema", "format", "title", "units", "materials", "sections", "gravity", "nodes", "members",
                          "supports", "springs", "loads", "prescribed", "contacts", "analysis", "stages"});
    if (doc_.contains("stages")) refuse_unstaged_keys(doc_);
    read_header();
    sections_.emplace(doc_);
    read_gravity();
    read_nodes();
    count_elements();  // before any node is made
    MemberMesh mesh(model_);
    read_members(mesh);
    mesh.finish();
    const std::vector<std::string> roller_paths =
        read_supports(doc_, [this](const json& value, const std::string& path) { return node_ref(value, path); }, model_);
    read_springs();
    loads_.emplace(
        model_, [this](const json& value, const std::string& path) { return node_ref(value, path); },
        [&mesh](int member, double at) { return mesh.station_node(member, at); });
    read_loads();
    read_prescribed();
    fix_free_rotations(model_);  // a moment on a hinge was refused with its load
    read_contacts();
    read_analysis(mesh.loaded_middles());
    check_skew_rollers(model_, roller_paths, loads_->prescribed_nodes());
    check_kept_states(model_);
    // The whole run's memory, before the run spends it (and before the checks below, which take
    // time in proportion to contacts × candidate elements).
    const MemoryEstimate estimate = estimate_memory(model_counts(model_, input_bytes_));
    check_memory(estimate, budget_, largest_part_path(estimate));
    check_resting_contacts();
    if (mechanisms_ == Mechanisms::refuse)
      if (auto mechanism = starting_mechanism(model_)) fail("supports", *mechanism);
    if (!model_.reference_prescribed.any()) model_.reference_prescribed.resize(0);  // nothing prescribed moves
    return std::move(model_);
  }

 private:
  void read_header() {
    if (doc_.contains("format")) {
      const std::string format = string(doc_["format"], "format");
      if (format != "tsmframe-model/1") fail("format", "unsupported format " + quote_text(format) + " (expected \"tsmframe-model/1\")");
    }
    if (doc_.contains("title")) model_.title = string(doc_["title"], "title");
    if (doc_.contains("units")) {
      expect_object(doc_["units"], "units");
      for (const auto& item : doc_["units"].items())
        model_.units[item.key()] = string(item.value(), child("units", item.key()));
    }
  }

  void read_nodes() {
    if (!doc_.contains("nodes")) fail("nodes", "missing (required)");
    const json& nodes = doc_["nodes"];
    expect_array(nodes, "nodes");
    if (nodes.empty()) fail("nodes", "the model has no nodes");
    for (size_t k = 0; k < nodes.size(); ++k) {
      const std::string path = child("nodes", k);
      expect_object(nodes[k], path);
      check_keys(nodes[k], path, {"id", "x", "y"});
      if (!nodes[k].contains("id")) fail(child(path, "id"), "missing (required)");
      const long id = bounded_integer(nodes[k]["id"], child(path, "id"), -2'000'000'000L, 2'000'000'000L);
      Node node{static_cast<int>(id), {required_number(nodes[k], "x", path), required_number(nodes[k], "y", path)}};
      if (ids_.count(node.id)) fail(child(path, "id"), "duplicate node id " + std::to_string(node.id));
      add_node(node);
    }
    Eigen::Vector2d lo = model_.nodes[0].position, hi = lo;
    for (const Node& n : model_.nodes) {
      lo = lo.cwiseMin(n.position);
      hi = hi.cwiseMax(n.position);
    }
    model_.size = (hi - lo).norm() > 0.0 ? (hi - lo).norm() : 1.0;
  }

  void add_node(const Node& node) {
    ids_[node.id] = model_.node_count();
    model_.nodes.push_back(node);
  }

  /// The nodes from ids_.size() on (the ones a member generated) become known by id.
  void register_nodes() {
    for (int k = static_cast<int>(ids_.size()); k < model_.node_count(); ++k) ids_[model_.nodes[k].id] = k;
  }

  /// A node given by id (`3`) or by coordinates (`[4.5, 0.0]`, matching exactly one node).
  int node_ref(const json& value, const std::string& path) const {
    return resolve_node(node_reference(value, path), path, model_, [this](long id) {
      const auto it = ids_.find(static_cast<int>(id));
      return id != static_cast<int>(id) || it == ids_.end() ? -1 : it->second;
    });
  }

  int required_node(const json& object, const std::string& path) const {
    if (!object.contains("node")) fail(child(path, "node"), "missing (required)");
    return node_ref(object["node"], child(path, "node"));
  }

  /// The elements and nodes the members make, counted before any is made: the element cap (at
  /// the member whose divisions pass it) and the memory budget. A divisions value that is no
  /// count of elements is left to read_member, which says why, member by member.
  void count_elements() const {
    if (!doc_.contains("members") || !doc_["members"].is_array()) return;
    const json& members = doc_["members"];
    double elements = 0.0;
    for (size_t k = 0; k < members.size(); ++k) {
      const json& m = members[k];
      double divisions = 1.0;
      if (m.is_object() && m.contains("divisions") && m["divisions"].is_number()) {
        const double d = m["divisions"].get<double>();
        if (d >= 1.0 && d <= max_divisions) divisions = std::floor(d);
      }
      elements += divisions;
      if (elements > max_elements)
        fail(child(child("members", k), "divisions"), "the model would have more than " + std::to_string(max_elements) + " elements");
    }
    ModelCounts counts;
    counts.input_bytes = input_bytes_;
    counts.elements = elements;
    counts.nodes = model_.node_count() + elements - static_cast<double>(members.size());  // each member's interior nodes
    counts.free_dofs = dofs_per_node * counts.nodes;
    check_memory(estimate_memory(counts), budget_, "members");
  }

  void read_members(MemberMesh& mesh) {
    if (!doc_.contains("members")) fail("members", "missing (required)");
    const json& members = doc_["members"];
    expect_array(members, "members");
    const std::vector<std::vector<double>> stations = member_stations(doc_, members.size());
    for (size_t k = 0; k < members.size(); ++k) {
      const std::string path = child("members", k);
      MemberInput member = read_member(members[k], path, k);
      member.stations = stations[k];
      try {
        mesh.add(member);
      } catch (const MeshError& e) {
        fail(mesh_error_path(path, e.value()), e.what());
      }
      register_nodes();
    }
  }

  /// "gravity": the acceleration [gx, gy] that gives every member whose material has a density
  /// its self-weight, density × A × g per unit length (a member load, scaled by λ).
  void read_gravity() {
    if (!doc_.contains("gravity")) return;
    const json& g = doc_["gravity"];
    if (!g.is_array() || g.size() != 2) fail("gravity", "expected [gx, gy] (the acceleration of gravity, e.g. [0, -9.81])");
    gravity_ = point(g, "gravity");
    if (!sections_->any_density())
      fail("gravity", "no material has a density: give materials.<name>.density (mass per volume) for the members to weigh");
  }

  /// Member k's values, in the order they are checked.
  MemberInput read_member(const json& m, const std::string& path, size_t k) {
    expect_object(m, path);
    check_keys(m, path, {"from", "to", "divisions", "element", "material", "section", "arc", "release", "end_springs", "load",
                         "foundation"});
    MemberInput member;
    if (!m.contains("from")) fail(child(path, "from"), "missing (required)");
    if (!m.contains("to")) fail(child(path, "to"), "missing (required)");
    member.from = node_ref(m["from"], child(path, "from"));
    member.to = node_ref(m["to"], child(path, "to"));
    if (m.contains("divisions")) member.divisions = bounded_integer(m["divisions"], child(path, "divisions"), 1, max_divisions);
    if (m.contains("element")) {
      const std::string kind = string(m["element"], child(path, "element"));
      if (kind == "timoshenko") member.theory = BeamTheory::timoshenko;
      else if (kind != "euler-bernoulli") fail(child(path, "element"), "unknown element " + quote_text(kind) + " (expected \"euler-bernoulli\" or \"timoshenko\")");
    }
    member.section = sections_->stiffness(m, path, member.theory);
    if (m.contains("load")) read_member_load(m["load"], child(path, "load"), member);
    if (const std::optional<double> mass = gravity_ ? sections_->mass_per_length(m) : std::nullopt)
      member.load += *mass * *gravity_;  // its self-weight per unit length, dead like every load
    if (m.contains("release")) {
      const std::string where = string(m["release"], child(path, "release"));
      member.release_start = where == "start" || where == "both";
      member.release_end = where == "end" || where == "both";
      if (!member.release_start && !member.release_end)
        fail(child(path, "release"), "unknown release " + quote_text(where) + " (expected \"start\", \"end\" or \"both\")");
      connected_members_.insert(static_cast<int>(k));
    }
    if (m.contains("end_springs")) {
      read_end_springs(m["end_springs"], child(path, "end_springs"), member);
      connected_members_.insert(static_cast<int>(k));
    }
    if (m.contains("arc")) member.arc = read_arc(m["arc"], child(path, "arc"));
    if (auto k = optional_number(m, "foundation", path)) member.foundation = positive(*k, child(path, "foundation"));
    return member;
  }

  /// "springs": linear springs to the ground at nodes — kx, ky, kr (along x, y, about the
  /// rotation) or k along a "direction" [dx, dy] — each a NodalSpring.
  void read_springs() {
    for_each_entry(doc_, "springs", {"node", "kx", "ky", "kr", "k", "direction"}, [&](const json& s, const std::string& path) {
      const int node = required_node(s, path);
      if (s.contains("k") != s.contains("direction")) fail(path, "give \"k\" with a \"direction\" [dx, dy], or kx, ky, kr");
      const size_t before = model_.springs.size();
      const auto add = [&](const char* key, NodalSpring::Kind kind, const Eigen::Vector2d& direction) {
        if (auto k = optional_number(s, key, path)) model_.springs.push_back({node, kind, direction, positive(*k, child(path, key))});
      };
      add("kx", NodalSpring::Kind::translation, Eigen::Vector2d::UnitX());
      add("ky", NodalSpring::Kind::translation, Eigen::Vector2d::UnitY());
      add("kr", NodalSpring::Kind::rotation, Eigen::Vector2d::UnitX());
      if (s.contains("direction")) {
        const Eigen::Vector2d d = point(s["direction"], child(path, "direction"));
        if (!(d.norm() > 0.0)) fail(child(path, "direction"), "must not be [0, 0]");
        add("k", NodalSpring::Kind::translation, d.normalized());
      }
      if (model_.springs.size() == before) fail(path, "give kx, ky, kr, or k with a direction");
    });
  }

  void read_loads() {
    if (doc_.contains("loads")) loads_->read_loads(doc_["loads"], "loads", model_.reference_load, model_.follower_forces);
  }

  void read_prescribed() {
    if (!doc_.contains("prescribed")) return;
    for (const PrescribedTarget& p : loads_->read_prescribed(doc_["prescribed"], "prescribed", false)) {
      model_.constrained[p.dof] = true;
      model_.reference_prescribed[p.dof] = p.value;
    }
  }

  /// Contacts resting on a beam as drawn start in contact; an element carries any number of
  /// them, all in one frame (as at every update): two resting on one element in different frames
  /// cannot both hold it.
  void check_resting_contacts() {
    std::vector<int> resting_on(model_.elements.size(), -1);
    const auto resting = resting_contacts(model_);
    for (int k = 0; k < static_cast<int>(model_.contacts.size()); ++k) {
      const auto& r = resting[k];
      if (!r) continue;
      const int other = resting_on[r->element];
      if (other >= 0 && !shares_element(model_.contacts[k].frame, model_.contacts[other].frame))
        fail("contacts[" + std::to_string(k) + "]",
             "rests on element " + std::to_string(model_.elements[r->element].id) + ", as contacts[" + std::to_string(other) +
                 "] does in the other frame: points on one element share its frame (give both the same \"frame\")");
      if (other < 0) resting_on[r->element] = k;
    }
  }

  /// What the contacts look up, in time linear in the model: each member's first element (a
  /// member's elements are consecutive) and the members whose elements end at each node (CSR).
  void index_members() {
    member_first_.assign(model_.member_count + 1, 0);
    for (const Element& e : model_.elements) ++member_first_[e.member + 1];
    for (int m = 0; m < model_.member_count; ++m) member_first_[m + 1] += member_first_[m];
    members_at_start_.assign(model_.node_count() + 1, 0);
    for (const Element& e : model_.elements) ++members_at_start_[e.start + 1], ++members_at_start_[e.end + 1];
    for (int k = 0; k < model_.node_count(); ++k) members_at_start_[k + 1] += members_at_start_[k];
    members_at_.resize(members_at_start_.back());
    std::vector<int> fill(members_at_start_.begin(), members_at_start_.end() - 1);
    for (const Element& e : model_.elements) {
      members_at_[fill[e.start]++] = e.member;
      members_at_[fill[e.end]++] = e.member;
    }
    has_contact_.assign(model_.node_count(), 0);
  }

  /// A member index (0-based, file order) at `path`.
  int member_index(const json& value, const std::string& path) const {
    const long index = integer(value, path);
    if (index < 0 || index >= model_.member_count)
      fail(path, "unknown member " + std::to_string(index) + " (members are numbered 0 to " + std::to_string(model_.member_count - 1) + " in file order)");
    return static_cast<int>(index);
  }

  /// The nodes of a member's elements, in element order (each element's two ends; inner nodes twice).
  std::vector<int> member_nodes(int member) const {
    std::vector<int> nodes;
    for (int e = member_first_[member]; e < member_first_[member + 1]; ++e) {
      nodes.push_back(model_.elements[e].start);
      nodes.push_back(model_.elements[e].end);
    }
    return nodes;
  }

  /// The members whose elements hold `node`.
  std::set<int> holding_members(int node) const {
    return {members_at_.begin() + members_at_start_[node], members_at_.begin() + members_at_start_[node + 1]};
  }

  void read_contacts() {
    if (!doc_.contains("contacts")) return;
    const json& contacts = doc_["contacts"];
    expect_array(contacts, "contacts");
    index_members();
    for (size_t k = 0; k < contacts.size(); ++k) {
      const std::string path = child("contacts", k);
      const json& c = contacts[k];
      contact_entries_.push_back(static_cast<int>(model_.contacts.size()));
      expect_object(c, path);
      check_keys(c, path, {"node", "nodes", "members", "between", "element", "frame", "normal", "gap", "edge", "max_stiffness_ratio", "sliding_tangent", "friction"});
      if (c.contains("between")) {
        read_between(c, path);
        continue;
      }
      if (c.contains("node") && c.contains("nodes")) fail(child(path, "nodes"), "give either node or nodes, not both");
      if (!c.contains("members")) fail(child(path, "members"), "missing (required, or give \"between\")");
      if (!c.contains("nodes")) {
        read_contact(c, path, required_node(c, path), child(path, "node"), false, c["members"], child(path, "members"));
        continue;
      }
      // Several contact nodes with the same options: a list of node references, or every node
      // of some members ({"members": [...]}: a ring's nodes against a plate), each a contact of
      // its own.
      const std::string npath = child(path, "nodes");
      const json& nodes = c["nodes"];
      std::vector<std::pair<int, std::string>> listed;  // (node, where it was named)
      if (nodes.is_object()) {
        check_keys(nodes, npath, {"members"});
        if (!nodes.contains("members")) fail(child(npath, "members"), "missing (required)");
        const std::string mpath = child(npath, "members");
        expect_array(nodes["members"], mpath);
        std::set<int> seen;
        for (size_t m = 0; m < nodes["members"].size(); ++m) {
          for (const int node : member_nodes(member_index(nodes["members"][m], child(mpath, m))))
            if (seen.insert(node).second) listed.emplace_back(node, child(mpath, m));
        }
      } else {
        expect_array(nodes, npath);
        for (size_t j = 0; j < nodes.size(); ++j) listed.emplace_back(node_ref(nodes[j], child(npath, j)), child(npath, j));
      }
      if (listed.empty()) fail(npath, "no node listed");
      for (const auto& [node, where] : listed) read_contact(c, path, node, where, true, c["members"], child(path, "members"));
    }
  }

  /// A contact entry between two beams, {"between": [[members A], [members B]]} (issue 27, part
  /// 3): every node of A's members a contact node on B's, and every node of B's on A's, with the
  /// entry's options; a node of both (a joint) touches neither. Where a node of one comes to rest
  /// on a node of the other, one of the two contacts carries the pair (contact/detection.cpp).
  void read_between(const json& c, const std::string& path) {
    const std::string bpath = child(path, "between");
    for (const char* key : {"node", "nodes", "members"})
      if (c.contains(key)) fail(child(path, key), "give either \"between\" or node(s) and members, not both");
    const json& between = c["between"];
    expect_array(between, bpath);
    if (between.size() != 2) fail(bpath, "expected two lists of member indices, [[A…], [B…]]");
    std::array<std::set<int>, 2> members;
    std::array<std::vector<int>, 2> nodes;  // each side's nodes, in its members' element order
    for (int side = 0; side < 2; ++side) {
      const std::string spath = child(bpath, side);
      expect_array(between[side], spath);
      if (between[side].empty()) fail(spath, "no member listed");
      std::set<int> seen;
      for (size_t m = 0; m < between[side].size(); ++m) {
        const int index = member_index(between[side][m], child(spath, m));
        if (!members[side].insert(index).second) fail(child(spath, m), "member " + std::to_string(index) + " listed twice");
        for (const int node : member_nodes(index))
          if (seen.insert(node).second) nodes[side].push_back(node);
      }
    }
    for (const int m : members[0])
      if (members[1].count(m)) fail(bpath, "member " + std::to_string(m) + " is on both sides");
    const auto on = [&](int side, int node) {
      const std::set<int> holding = holding_members(node);
      return std::any_of(holding.begin(), holding.end(), [&](int m) { return members[side].count(m) > 0; });
    };
    for (int side = 0; side < 2; ++side) {
      const json other = json(std::vector<int>(members[1 - side].begin(), members[1 - side].end()));
      for (const int node : nodes[side])
        if (!on(1 - side, node)) read_contact(c, path, node, child(bpath, side), true, other, child(bpath, 1 - side));
    }
  }

  /// One contact entry's options for the contact node `node`, named at `node_path` (`named`: one
  /// of several nodes of the entry, whose id the messages then give).
  void read_contact(const json& c, const std::string& path, int node, const std::string& node_path, bool named,
                    const json& members, const std::string& mpath) {
    ContactSpec spec;
    spec.node = node;
    const std::string which = named ? "the contact node " + std::to_string(model_.nodes[node].id) : "the contact node";
    const std::set<int> holding = holding_members(spec.node);
    // Hinged or sprung members carry contacts in the chord frame (their ends condensed out of
    // the contact element's law); the cantilever-coordinate element has no such form.
    const bool cantilever = c.contains("frame") && c["frame"].is_string() && c["frame"].get<std::string>() == "cantilever";
    const std::set<int> refused = cantilever ? connected_members_ : std::set<int>{};
    if (members.is_string()) {
      if (members.get<std::string>() != "all") fail(mpath, "expected \"all\" or a list of member indices");
      for (int m = 0; m < model_.member_count; ++m)
        if (!holding.count(m) && !refused.count(m)) spec.members.push_back(m);
    } else {
      expect_array(members, mpath);
      for (size_t m = 0; m < members.size(); ++m) {
        const int index = member_index(members[m], child(mpath, m));
        if (holding.count(index)) fail(child(mpath, m), which + " belongs to member " + std::to_string(index));
        if (refused.count(index))
          fail(child(mpath, m), "member " + std::to_string(index) + " has a moment release or an end spring: the cantilever-coordinate contact element does not support such members (the chord frame does)");
        spec.members.push_back(index);
      }
    }
    if (spec.members.empty())
      fail(mpath, (named ? "no member for " + which + " to touch" : std::string("no member to touch")) +
                      (refused.empty() ? "" : " (hinged or sprung members carry no cantilever-coordinate contact)"));
    if (c.contains("element")) {
      const std::string element = string(c["element"], child(path, "element"));
      if (element != "euler-bernoulli" && element != "timoshenko") fail(child(path, "element"), "unknown element " + quote_text(element) + " (expected \"euler-bernoulli\" or \"timoshenko\")");
      spec.theory = element == "timoshenko" ? BeamTheory::timoshenko : BeamTheory::euler_bernoulli;
      if (spec.theory == BeamTheory::timoshenko) {
        spec.member_shear_flexibility.assign(model_.member_count, 0.0);
        for (int m : spec.members) {
          try {
            spec.member_shear_flexibility[m] = sections_->stiffness(doc_["members"][m], child("members", m), BeamTheory::timoshenko).shear_flexibility;
          } catch (const InputError& e) {
            fail(child(path, "element"), "a Timoshenko contact on member " + std::to_string(m) + " needs its shear data: " + e.reason());
          }
        }
      }
    }
    read_contact_law_options(c, path, spec);
    if (has_contact_[spec.node])
      fail(node_path, (named ? "node " + std::to_string(model_.nodes[node].id) + " already has" : std::string("this node already has")) +
                          " a contact entry: list all its members in one entry");
    has_contact_[spec.node] = 1;
    model_.contacts.push_back(std::move(spec));
  }

  /// Linearised buckling (solver/buckling) takes the reference load on the drawn structure:
  /// nothing whose stiffness or load the linear solution leaves out.
  void check_buckling() const {
    const auto refuse = [](const std::string& what) {
      fail("analysis.buckling", "linearised buckling is not available with " + what + " (it takes the reference load on the "
                                "drawn structure; run the path instead, whose steps report their stability)");
    };
    if (!model_.contacts.empty()) refuse("contacts");
    if (!model_.stages.empty()) refuse("stages");
    if (!model_.follower_forces.empty() ||
        std::any_of(model_.member_extras.begin(), model_.member_extras.end(), [](const MemberExtras& x) { return x.pressure != 0.0; }))
      refuse("follower loads");
    if (model_.reference_prescribed.size() > 0 && !model_.reference_prescribed.isZero()) refuse("prescribed displacements");
  }

  /// The analysis settings, then the stages (whose output defaults to the analysis's), then the
  /// monitored nodes (by default those the loads and stages name).
  void read_analysis(const std::vector<int>& loaded_middles) {
    if (doc_.contains("analysis"))
      read_analysis_settings(doc_["analysis"], model_, [this](const json& value, const std::string& path) { return node_ref(value, path); });
    contact_entries_.push_back(static_cast<int>(model_.contacts.size()));  // the count, after the last entry's first
    if (doc_.contains("stages")) model_.stages = loads_->read_stages(doc_["stages"], model_.analysis.output, contact_entries_);
    if (model_.analysis.buckling_modes > 0) check_buckling();
    std::set<int> named = loads_->loaded_nodes();
    if (!model_.stages.empty()) named.insert(loads_->prescribed_nodes().begin(), loads_->prescribed_nodes().end());
    if (!doc_.contains("analysis") || !doc_["analysis"].contains("monitor"))
      model_.analysis.monitor = default_monitor(model_, named, loaded_middles);
  }

  const json& doc_;
  const MemoryBudget& budget_;
  double input_bytes_ = 0.0;
  Mechanisms mechanisms_ = Mechanisms::refuse;
  Model model_;
  std::optional<SectionTable> sections_;  ///< read after the header
  std::optional<Eigen::Vector2d> gravity_;  ///< "gravity", if given
  std::set<int> connected_members_;  ///< members with a moment release or an end spring ("release", "end_springs")
  std::optional<LoadsReader> loads_;  ///< once the supports are read
  std::vector<int> contact_entries_;  ///< the first contact of each "contacts" entry (LoadsReader::read_stages)
  std::unordered_map<int, int> ids_;
  // The contacts' look-ups (index_members): each member's first element, the members at each
  // node (CSR), and the nodes that have a contact entry already.
  std::vector<int> member_first_, members_at_start_, members_at_;
  std::vector<char> has_contact_;
};

}  // namespace

Model read_model(const json& document, const MemoryBudget& budget, double input_bytes, Mechanisms mechanisms) {
  return Reader(document, budget, input_bytes, mechanisms).read();
}

Model read_model(const json& document) { return read_model(document, memory_budget()); }

Model read_model_text(const std::string& text, Mechanisms mechanisms) {
  const MemoryBudget budget = memory_budget();
  const double bytes = static_cast<double>(text.size());
  check_memory(estimate_memory({.input_bytes = bytes}), budget, "(document)");  // before the document is parsed
  return read_model(parse_json(text), budget, bytes, mechanisms);
}

Model read_model_file(const std::string& path, Mechanisms mechanisms) {
  try {
    const MemoryBudget budget = memory_budget();
    json document;
    double bytes = 0.0;
    {
      const std::string text = read_input_file(path);
      bytes = static_cast<double>(text.size());
      check_memory(estimate_memory({.input_bytes = bytes}), budget, "(document)");
      document = parse_json(text);
    }
    return read_model(document, budget, bytes, mechanisms);
  } catch (const MemoryShortage& e) {
    throw MemoryShortage(path, e.what());
  } catch (const SystemError& e) {
    throw SystemError(path, e.what());
  }
}

}  // namespace tsm::io
