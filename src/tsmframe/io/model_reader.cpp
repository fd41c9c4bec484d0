#include "tsmframe/io/model_reader.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <numbers>
#include <optional>
#include <set>
#include <sstream>
#include <unordered_map>

#include "tsmframe/io/input_error.hpp"
#include "tsmframe/io/json_writer.hpp"
#include "tsmframe/model/mechanism.hpp"
#include "tsmframe/model/hinges.hpp"
#include "tsmframe/model/node_lookup.hpp"
#include "tsmframe/model/resting_contact.hpp"

namespace tsm::io {
namespace {

using nlohmann::json;

constexpr long max_divisions = 10'000'000;        // per member: a typo must not exhaust memory
constexpr long max_elements = 20'000'000;         // per model
constexpr long max_steps = 10'000'000;
constexpr double max_kept_state_bytes = 8e9;  // the converged states an output selection keeps (check_kept_states)

std::string quote_text(const std::string& text) { return json(text).dump(); }

/// `parent.key`, or `parent["odd key"]` when the key is not a plain identifier.
std::string child(const std::string& parent, const std::string& key) {
  bool plain = !key.empty() && !std::isdigit(static_cast<unsigned char>(key[0]));
  for (char c : key) plain = plain && (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-');
  if (!plain) return parent + "[" + quote_text(key) + "]";
  return parent.empty() ? key : parent + "." + key;
}
std::string child(const std::string& parent, size_t index) { return parent + "[" + std::to_string(index) + "]"; }

const char* type_name(const json& value) {
  if (value.is_number()) return "a number";
  if (value.is_string()) return "a string";
  if (value.is_boolean()) return "true/false";
  if (value.is_array()) return "a list";
  if (value.is_object()) return "an object";
  return "null";
}

[[noreturn]] void fail(const std::string& path, const std::string& reason) { throw InputError(path, reason); }

void expect_object(const json& value, const std::string& path) {
  if (!value.is_object()) fail(path, std::string("expected an object, found ") + type_name(value));
}
void expect_array(const json& value, const std::string& path) {
  if (!value.is_array()) fail(path, std::string("expected a list, found ") + type_name(value));
}

/// Every key must be one of `allowed` (or "extra", which is ignored).
void check_keys(const json& object, const std::string& path, std::initializer_list<const char*> allowed) {
  for (const auto& item : object.items()) {
    if (item.key() == "extra") continue;
    bool known = false;
    for (const char* name : allowed) known = known || item.key() == name;
    if (known) continue;
    std::string list;
    for (const char* name : allowed) list += (list.empty() ? "" : ", ") + std::string(name);
    fail(child(path, item.key()), "unknown key " + quote_text(item.key()) + " (expected one of: " + list + ")");
  }
}

constexpr double largest_number = 1e50;  // |x| of any number in a model

double number(const json& value, const std::string& path) {
  if (!value.is_number()) fail(path, std::string("expected a number, found ") + type_name(value));
  const double x = value.get<double>();
  if (!std::isfinite(x)) fail(path, "the number is not finite");
  // No unit system needs more, and products of a few such numbers (EA · l, a load times a
  // displacement) would overflow to infinity mid-analysis instead of failing here.
  if (std::abs(x) > largest_number) fail(path, "beyond ±1e50 (" + format_number(x) + "): no unit system needs it, and products of such numbers overflow");
  return x;
}

std::optional<double> optional_number(const json& object, const char* key, const std::string& path) {
  if (!object.contains(key)) return std::nullopt;
  return number(object.at(key), child(path, key));
}

double required_number(const json& object, const char* key, const std::string& path) {
  if (!object.contains(key)) fail(child(path, key), "missing (required)");
  return number(object.at(key), child(path, key));
}

double positive(double value, const std::string& path) {
  if (!(value > 0.0)) {
    std::ostringstream os;
    os << "must be positive, got " << value;
    fail(path, os.str());
  }
  return value;
}

long integer(const json& value, const std::string& path) {
  if (value.is_number_integer()) return value.get<long>();
  if (value.is_number_float()) {
    const double x = value.get<double>();
    if (std::floor(x) == x && std::abs(x) < 9e15) return static_cast<long>(x);
  }
  fail(path, std::string("expected a whole number, found ") + (value.is_number() ? value.dump() : type_name(value)));
}

long bounded_integer(const json& value, const std::string& path, long lo, long hi) {
  const long n = integer(value, path);
  if (n < lo || n > hi) fail(path, "must be between " + std::to_string(lo) + " and " + std::to_string(hi) + ", got " + std::to_string(n));
  return n;
}

std::string string(const json& value, const std::string& path) {
  if (!value.is_string()) fail(path, std::string("expected a string, found ") + type_name(value));
  return value.get<std::string>();
}

bool boolean(const json& value, const std::string& path) {
  if (!value.is_boolean()) fail(path, std::string("expected true or false, found ") + type_name(value));
  return value.get<bool>();
}

Eigen::Vector2d point(const json& value, const std::string& path) {
  if (!value.is_array() || value.size() != 2) fail(path, "expected a point [x, y]");
  return {number(value[0], child(path, 0)), number(value[1], child(path, 1))};
}

int dof_from_name(const std::string& name, const std::string& path) {
  if (name == "ux") return ux;
  if (name == "uy") return uy;
  if (name == "rz") return rz;
  fail(path, "unknown dof " + quote_text(name) + " (expected ux, uy or rz)");
}

struct Material {
  double E = 0.0;
  std::optional<double> G;
};

struct Section {
  double A = 0.0, I = 0.0;
  std::optional<double> shear_area;
};

class Reader {
 public:
  explicit Reader(const json& document) : doc_(document) {}

  Model read() {
    expect_object(doc_, "(document)");
    check_keys(doc_, "", {"format", "title", "units", "materials", "sections", "nodes", "members", "supports",
                          "loads", "prescribed", "contacts", "analysis"});
    read_header();
    read_materials();
    read_sections();
    read_nodes();
    read_members();
    model_.constrained.assign(model_.dof_count(), false);
    model_.reference_load = Eigen::VectorXd::Zero(model_.dof_count());
    model_.reference_prescribed = Eigen::VectorXd::Zero(model_.dof_count());
    read_supports();
    read_loads();
    read_prescribed();
    fix_free_rotations();
    read_contacts();
    check_resting_contacts();
    read_analysis();
    check_kept_states();
    if (auto mechanism = find_mechanism(model_)) fail("supports", *mechanism);
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

  void read_materials() {
    if (!doc_.contains("materials")) fail("materials", "missing (required)");
    expect_object(doc_["materials"], "materials");
    for (const auto& item : doc_["materials"].items()) {
      const std::string path = child("materials", item.key());
      const json& m = item.value();
      expect_object(m, path);
      check_keys(m, path, {"E", "G", "nu"});
      Material material;
      material.E = positive(required_number(m, "E", path), child(path, "E"));
      if (m.contains("G") && m.contains("nu")) fail(path, "give G or nu, not both");
      if (auto G = optional_number(m, "G", path)) material.G = positive(*G, child(path, "G"));
      if (auto nu = optional_number(m, "nu", path)) {
        if (!(*nu > -1.0 && *nu < 0.5)) fail(child(path, "nu"), "Poisson's ratio must lie in (-1, 0.5)");
        material.G = material.E / (2.0 * (1.0 + *nu));
      }
      materials_[item.key()] = material;
    }
  }

  void read_sections() {
    if (!doc_.contains("sections")) fail("sections", "missing (required)");
    expect_object(doc_["sections"], "sections");
    for (const auto& item : doc_["sections"].items()) {
      const std::string path = child("sections", item.key());
      const json& s = item.value();
      expect_object(s, path);
      check_keys(s, path, {"A", "I", "shear_area"});
      Section section;
      section.A = positive(required_number(s, "A", path), child(path, "A"));
      section.I = positive(required_number(s, "I", path), child(path, "I"));
      if (auto shear = optional_number(s, "shear_area", path)) section.shear_area = positive(*shear, child(path, "shear_area"));
      sections_[item.key()] = section;
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

  /// A node given by id (`3`) or by coordinates (`[4.5, 0.0]`, matching exactly one node).
  int node_ref(const json& value, const std::string& path) const {
    if (value.is_array()) {
      std::string problem;
      const int found = node_at(model_, point(value, path), problem);
      if (found < 0) fail(path, problem);
      return found;
    }
    if (!value.is_number()) fail(path, std::string("expected a node id or [x, y], found ") + type_name(value));
    const long id = integer(value, path);
    const auto it = ids_.find(static_cast<int>(id));
    if (id != static_cast<int>(id) || it == ids_.end()) fail(path, "unknown node " + std::to_string(id));
    return it->second;
  }

  int required_node(const json& object, const std::string& path) const {
    if (!object.contains("node")) fail(child(path, "node"), "missing (required)");
    return node_ref(object["node"], child(path, "node"));
  }

  void read_members() {
    if (!doc_.contains("members")) fail("members", "missing (required)");
    const json& members = doc_["members"];
    expect_array(members, "members");
    int next_id = std::numeric_limits<int>::min();
    for (const Node& n : model_.nodes) next_id = std::max(next_id, n.id + 1);
    long element_count = 0;
    for (size_t k = 0; k < members.size(); ++k) {
      const std::string path = child("members", k);
      const json& m = members[k];
      expect_object(m, path);
      check_keys(m, path, {"from", "to", "divisions", "element", "material", "section", "arc", "release", "end_springs", "load"});
      if (!m.contains("from")) fail(child(path, "from"), "missing (required)");
      if (!m.contains("to")) fail(child(path, "to"), "missing (required)");
      const int from = node_ref(m["from"], child(path, "from"));
      const int to = node_ref(m["to"], child(path, "to"));
      const long divisions = m.contains("divisions") ? bounded_integer(m["divisions"], child(path, "divisions"), 1, max_divisions) : 1;
      element_count += divisions;
      if (element_count > max_elements) fail(child(path, "divisions"), "the model would have more than " + std::to_string(max_elements) + " elements");

      BeamTheory theory = BeamTheory::euler_bernoulli;
      if (m.contains("element")) {
        const std::string kind = string(m["element"], child(path, "element"));
        if (kind == "timoshenko") theory = BeamTheory::timoshenko;
        else if (kind != "euler-bernoulli") fail(child(path, "element"), "unknown element " + quote_text(kind) + " (expected \"euler-bernoulli\" or \"timoshenko\")");
      }
      const element::SectionStiffness section = section_stiffness(m, path, theory);
      std::array<double, 2> distributed{0.0, 0.0};  // "load": force per unit length (global x, y)
      double pressure = 0.0;                         // … and a follower load normal to the elements
      if (m.contains("load")) {
        const std::string lpath = child(path, "load");
        expect_object(m["load"], lpath);
        check_keys(m["load"], lpath, {"fx", "fy", "pressure"});
        if (auto fx = optional_number(m["load"], "fx", lpath)) distributed[0] = *fx;
        if (auto fy = optional_number(m["load"], "fy", lpath)) distributed[1] = *fy;
        if (auto p = optional_number(m["load"], "pressure", lpath)) pressure = *p;
        if (distributed[0] == 0.0 && distributed[1] == 0.0 && pressure == 0.0)
          fail(lpath, "give fx, fy or pressure (force per unit length)");
      }
      bool release_from = false, release_to = false;  // hinges at the member's ends
      if (m.contains("release")) {
        const std::string where = string(m["release"], child(path, "release"));
        if (where == "start" || where == "both") release_from = true;
        if (where == "end" || where == "both") release_to = true;
        if (!release_from && !release_to)
          fail(child(path, "release"), "unknown release " + quote_text(where) + " (expected \"start\", \"end\" or \"both\")");
        connected_members_.insert(static_cast<int>(k));
      }
      double flexibility_from = 0.0, flexibility_to = 0.0;  // rotational springs at the ends (semi-rigid)
      if (m.contains("end_springs")) {
        const std::string spath = child(path, "end_springs");
        expect_object(m["end_springs"], spath);
        check_keys(m["end_springs"], spath, {"start", "end"});
        for (const char* end : {"start", "end"}) {
          if (!m["end_springs"].contains(end)) continue;
          const std::string epath = child(spath, end);
          const double stiffness = number(m["end_springs"][end], epath);
          if (!(stiffness > 0.0) || !std::isfinite(stiffness))
            fail(epath, "a rotational spring's stiffness (moment per radian) must be a positive finite number (a hinge is \"release\")");
          if ((std::string(end) == "start" && release_from) || (std::string(end) == "end" && release_to))
            fail(epath, "that end is released (a hinge): a spring there holds nothing");
          (std::string(end) == "start" ? flexibility_from : flexibility_to) = 1.0 / stiffness;
        }
        if (m["end_springs"].empty()) fail(spath, "give start or end (rotational stiffness, moment per radian)");
        connected_members_.insert(static_cast<int>(k));
      }

      if (pressure != 0.0 || flexibility_from > 0.0 || flexibility_to > 0.0) {
        model_.member_extras.resize(members.size());
        model_.member_extras[k] = {pressure, flexibility_from, flexibility_to};
      }
      const Eigen::Vector2d a = model_.nodes[from].position, b = model_.nodes[to].position;
      std::vector<Eigen::Vector2d> interior;
      if (m.contains("arc")) {
        interior = arc_points(m["arc"], child(path, "arc"), a, b, from == to, divisions);
      } else {
        if (from == to || (b - a).norm() <= 1e-12 * model_.size) fail(path, "zero-length member (from and to are the same point)");
        for (long d = 1; d < divisions; ++d) interior.push_back(a + (b - a) * (static_cast<double>(d) / divisions));
      }
      int previous = from;
      for (long d = 1; d <= divisions; ++d) {
        int current = to;
        if (d < divisions) {
          if (next_id == std::numeric_limits<int>::max()) fail(path, "node ids overflow");
          add_node({next_id++, interior[d - 1]});
          current = model_.node_count() - 1;
        }
        Element e;
        e.id = static_cast<int>(model_.elements.size()) + 1;
        e.start = previous;
        e.end = current;
        e.member = static_cast<int>(k);
        e.theory = theory;
        e.release_start = release_from && d == 1;
        e.release_end = release_to && d == divisions;
        e.member_start = d == 1;
        e.member_end = d == divisions;
        e.section = section;
        model_.elements.push_back(e);
        if (distributed[0] != 0.0 || distributed[1] != 0.0) {  // per unit length along the drawn element, half to each end
          const double length = (model_.nodes[e.end].position - model_.nodes[e.start].position).norm();
          member_loads_.push_back({e.start, e.end, distributed[0] * length / 2.0, distributed[1] * length / 2.0});
        }
        if (m.contains("load") && divisions >= 2 && d == divisions / 2) loaded_member_middles_.push_back(current);
        previous = current;
      }
    }
    model_.member_count = static_cast<int>(members.size());
    model_.nodes.shrink_to_fit();  // no growth slack kept through the analysis
    model_.elements.shrink_to_fit();
  }

  element::SectionStiffness section_stiffness(const json& m, const std::string& path, BeamTheory theory) const {
    if (!m.contains("material")) fail(child(path, "material"), "missing (required)");
    if (!m.contains("section")) fail(child(path, "section"), "missing (required)");
    const std::string material_name = string(m["material"], child(path, "material"));
    const std::string section_name = string(m["section"], child(path, "section"));
    const auto material = materials_.find(material_name);
    if (material == materials_.end()) fail(child(path, "material"), "unknown material " + quote_text(material_name));
    const auto section = sections_.find(section_name);
    if (section == sections_.end()) fail(child(path, "section"), "unknown section " + quote_text(section_name));
    element::SectionStiffness s;
    s.EA = material->second.E * section->second.A;
    s.EI = material->second.E * section->second.I;
    if (theory == BeamTheory::timoshenko) {
      if (!material->second.G) fail(child(path, "material"), "material " + quote_text(material_name) + " has no G (or nu), which Timoshenko elements need");
      if (!section->second.shear_area) fail(child(path, "section"), "section " + quote_text(section_name) + " has no shear_area, which Timoshenko elements need");
      s.shear_flexibility = s.EI / (*material->second.G * *section->second.shear_area);  // Ψ = EI/(G A_s), Eq. 8
    }
    return s;
  }

  std::vector<Eigen::Vector2d> arc_points(const json& arc, const std::string& path, const Eigen::Vector2d& a,
                                          const Eigen::Vector2d& b, bool closed, long divisions) const {
    expect_object(arc, path);
    check_keys(arc, path, {"center", "sweep"});
    if (!arc.contains("center")) fail(child(path, "center"), "missing (required)");
    const Eigen::Vector2d centre = point(arc["center"], child(path, "center"));
    const double sweep = required_number(arc, "sweep", path);
    const double two_pi = 2.0 * std::numbers::pi;
    if (sweep == 0.0 || std::abs(sweep) > two_pi * (1 + 1e-12)) fail(child(path, "sweep"), "must be non-zero and at most 2π in size");
    const double radius = (a - centre).norm();
    if (radius <= 1e-12 * model_.size) fail(child(path, "center"), "the centre coincides with the start node");
    if (std::abs((b - centre).norm() - radius) > 1e-6 * radius) fail(child(path, "center"), "the start and end nodes are not on one circle about the centre");
    const double start = std::atan2(a.y() - centre.y(), a.x() - centre.x());
    const Eigen::Vector2d reached = centre + radius * Eigen::Vector2d(std::cos(start + sweep), std::sin(start + sweep));
    if ((reached - b).norm() > 1e-6 * radius) {
      // Name the sweeps that do reach it: the short way round and the long one (a closed ring: ±2π).
      double to_end = std::atan2(b.y() - centre.y(), b.x() - centre.x()) - start;
      to_end = std::remainder(to_end, two_pi);
      const double other = to_end > 0.0 ? to_end - two_pi : to_end + two_pi;
      fail(child(path, "sweep"), "the sweep from the start node does not end at the end node (" + format_number(to_end) +
                                     " or " + format_number(other) + " does)");
    }
    if (closed != (std::abs(std::abs(sweep) - two_pi) < 1e-9)) fail(path, "a full circle must start and end at the same node");
    std::vector<Eigen::Vector2d> points;
    for (long d = 1; d < divisions; ++d) {
      const double angle = start + sweep * static_cast<double>(d) / divisions;
      points.push_back(centre + radius * Eigen::Vector2d(std::cos(angle), std::sin(angle)));
    }
    return points;
  }

  void read_supports() {
    if (!doc_.contains("supports")) return;
    const json& supports = doc_["supports"];
    expect_array(supports, "supports");
    for (size_t k = 0; k < supports.size(); ++k) {
      const std::string path = child("supports", k);
      const json& s = supports[k];
      expect_object(s, path);
      check_keys(s, path, {"node", "fix", "type"});
      const int node = required_node(s, path);
      if (!s.contains("fix") && !s.contains("type")) fail(path, "give \"fix\" (a list of ux, uy, rz) or \"type\"");
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
      for (int dof : fixed) model_.constrained[dofs_per_node * node + dof] = true;
    }
  }

  void read_loads() {
    for (const MemberLoad& l : member_loads_) {  // members' distributed loads, lumped at the element ends
      model_.reference_load[dofs_per_node * l.start + ux] += l.fx;
      model_.reference_load[dofs_per_node * l.start + uy] += l.fy;
      model_.reference_load[dofs_per_node * l.end + ux] += l.fx;
      model_.reference_load[dofs_per_node * l.end + uy] += l.fy;
    }
    if (!doc_.contains("loads")) return;
    const json& loads = doc_["loads"];
    expect_array(loads, "loads");
    const std::vector<char> hinge = hinge_nodes(model_);
    for (size_t k = 0; k < loads.size(); ++k) {
      const std::string path = child("loads", k);
      const json& l = loads[k];
      expect_object(l, path);
      check_keys(l, path, {"node", "fx", "fy", "mz"});
      const int node = required_node(l, path);
      const char* keys[3] = {"fx", "fy", "mz"};
      for (int dof = 0; dof < dofs_per_node; ++dof)
        if (auto value = optional_number(l, keys[dof], path)) {
          if (dof == rz && *value != 0.0 && hinge[node] && !model_.constrained[dofs_per_node * node + rz])
            fail(child(path, "mz"), "node " + std::to_string(model_.nodes[node].id) +
                                        " is a hinge: every element end there is released, so it carries no moment");
          model_.reference_load[dofs_per_node * node + dof] += *value;
          if (*value != 0.0) nodally_loaded_.insert(node);
        }
    }
  }

  void read_prescribed() {
    if (!doc_.contains("prescribed")) return;
    const json& prescribed = doc_["prescribed"];
    expect_array(prescribed, "prescribed");
    std::set<int> seen;
    for (size_t k = 0; k < prescribed.size(); ++k) {
      const std::string path = child("prescribed", k);
      const json& p = prescribed[k];
      expect_object(p, path);
      check_keys(p, path, {"node", "ux", "uy", "rz"});
      const int node = required_node(p, path);
      const char* keys[3] = {"ux", "uy", "rz"};
      bool any = false;
      for (int dof = 0; dof < dofs_per_node; ++dof) {
        auto value = optional_number(p, keys[dof], path);
        if (!value) continue;
        any = true;
        const int g = dofs_per_node * node + dof;
        if (!seen.insert(g).second) fail(child(path, keys[dof]), std::string("this dof is already prescribed by an earlier entry"));
        model_.constrained[g] = true;
        model_.reference_prescribed[g] = *value;
      }
      if (!any) fail(path, "give at least one of ux, uy, rz");
    }
  }

  /// Contacts resting on a beam as drawn start in contact, one per element (as at every
  /// update): two resting on one element cannot both hold it.
  void check_resting_contacts() {
    std::vector<int> resting_on(model_.elements.size(), -1);
    for (int k = 0; k < static_cast<int>(model_.contacts.size()); ++k) {
      const auto r = resting_contact(model_, model_.contacts[k]);
      if (!r) continue;
      if (resting_on[r->element] >= 0)
        fail("contacts[" + std::to_string(k) + "]",
             "rests on element " + std::to_string(model_.elements[r->element].id) + ", as contacts[" +
                 std::to_string(resting_on[r->element]) + "] does: one contact per element (give that member more divisions)");
      resting_on[r->element] = k;
    }
  }

  /// A node whose rotation no element end holds has it fixed: a node no element holds (FORMAT.md:
  /// a rigid pusher), or a hinge where every element end is released.
  void fix_free_rotations() {
    const std::vector<char> hinge = hinge_nodes(model_);
    std::vector<bool> held(model_.node_count(), false);
    for (const Element& e : model_.elements) held[e.start] = held[e.end] = true;
    for (int k = 0; k < model_.node_count(); ++k)  // a moment on a hinge was refused with its load
      if (!held[k] || hinge[k]) model_.constrained[dofs_per_node * k + rz] = true;
  }

  void read_contacts() {
    if (!doc_.contains("contacts")) return;
    const json& contacts = doc_["contacts"];
    expect_array(contacts, "contacts");
    for (size_t k = 0; k < contacts.size(); ++k) {
      const std::string path = child("contacts", k);
      const json& c = contacts[k];
      expect_object(c, path);
      check_keys(c, path, {"node", "nodes", "members", "element", "frame", "gap", "edge", "max_stiffness_ratio", "sliding_tangent"});
      if (c.contains("node") && c.contains("nodes")) fail(child(path, "nodes"), "give either node or nodes, not both");
      if (!c.contains("nodes")) {
        read_contact(c, path, required_node(c, path), child(path, "node"), false);
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
          const long index = integer(nodes["members"][m], child(mpath, m));
          if (index < 0 || index >= model_.member_count) fail(child(mpath, m), "unknown member " + std::to_string(index) + " (members are numbered 0 to " + std::to_string(model_.member_count - 1) + " in file order)");
          for (const Element& e : model_.elements)
            if (e.member == index)
              for (const int node : {e.start, e.end})
                if (seen.insert(node).second) listed.emplace_back(node, child(mpath, m));
        }
      } else {
        expect_array(nodes, npath);
        for (size_t j = 0; j < nodes.size(); ++j) listed.emplace_back(node_ref(nodes[j], child(npath, j)), child(npath, j));
      }
      if (listed.empty()) fail(npath, "no node listed");
      for (const auto& [node, where] : listed) read_contact(c, path, node, where, true);
    }
  }

  /// One contact entry's options for the contact node `node`, named at `node_path` (`named`: one
  /// of several nodes of the entry, whose id the messages then give).
  void read_contact(const json& c, const std::string& path, int node, const std::string& node_path, bool named) {
    ContactSpec spec;
    spec.node = node;
    const std::string which = named ? "the contact node " + std::to_string(model_.nodes[node].id) : "the contact node";
    if (!c.contains("members")) fail(child(path, "members"), "missing (required)");
    const json& members = c["members"];
    const std::string mpath = child(path, "members");
    std::set<int> holding;
    for (const Element& e : model_.elements)
      if (e.start == spec.node || e.end == spec.node) holding.insert(e.member);
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
        const long index = integer(members[m], child(mpath, m));
        if (index < 0 || index >= model_.member_count) fail(child(mpath, m), "unknown member " + std::to_string(index) + " (members are numbered 0 to " + std::to_string(model_.member_count - 1) + " in file order)");
        if (holding.count(static_cast<int>(index))) fail(child(mpath, m), which + " belongs to member " + std::to_string(index));
        if (refused.count(static_cast<int>(index)))
          fail(child(mpath, m), "member " + std::to_string(index) + " has a moment release or an end spring: the cantilever-coordinate contact element does not support such members (the chord frame does)");
        spec.members.push_back(static_cast<int>(index));
      }
    }
    if (spec.members.empty())
      fail(mpath, (named ? "no member for " + which + " to touch" : std::string("no member to touch")) +
                      (refused.empty() ? "" : " (hinged or sprung members carry no cantilever-coordinate contact)"));
    if (c.contains("element")) {
      spec.element = string(c["element"], child(path, "element"));
      if (spec.element != "euler-bernoulli" && spec.element != "timoshenko") fail(child(path, "element"), "unknown element " + quote_text(spec.element) + " (expected \"euler-bernoulli\" or \"timoshenko\")");
      if (spec.element == "timoshenko") {
        spec.member_shear_flexibility.assign(model_.member_count, 0.0);
        for (int m : spec.members) {
          try {
            spec.member_shear_flexibility[m] = section_stiffness(doc_["members"][m], child("members", m), BeamTheory::timoshenko).shear_flexibility;
          } catch (const InputError& e) {
            fail(child(path, "element"), "a Timoshenko contact on member " + std::to_string(m) + " needs its shear data: " + e.reason());
          }
        }
      }
    }
    if (c.contains("frame")) {
      spec.frame = string(c["frame"], child(path, "frame"));
      if (spec.frame != "chord" && spec.frame != "cantilever") fail(child(path, "frame"), "unknown frame " + quote_text(spec.frame) + " (expected \"chord\" or \"cantilever\")");
    }
    if (auto edge = optional_number(c, "edge", path)) {
      if (!(*edge >= 1e-12 && *edge <= 0.25)) fail(child(path, "edge"), "must lie between 1e-12 and 0.25 (a fraction of the element length)");
      spec.edge = *edge;
    }
    if (auto ratio = optional_number(c, "max_stiffness_ratio", path)) {
      if (!(*ratio >= 1.0)) fail(child(path, "max_stiffness_ratio"), "must be at least 1 (the contact's stiffness at most this many times the stiffest element holding its node)");
      spec.max_stiffness_ratio = *ratio;
    }
    if (c.contains("sliding_tangent")) spec.sliding_tangent = boolean(c["sliding_tangent"], child(path, "sliding_tangent"));
    if (auto gap = optional_number(c, "gap", path)) {
      if (*gap < 0.0) fail(child(path, "gap"), "must not be negative");
      spec.gap = *gap;
    }
    for (const ContactSpec& other : model_.contacts)
      if (other.node == spec.node)
        fail(node_path, (named ? "node " + std::to_string(model_.nodes[node].id) + " already has" : std::string("this node already has")) +
                            " a contact entry: list all its members in one entry");
    model_.contacts.push_back(spec);
  }

  void read_analysis() {
    AnalysisSettings& a = model_.analysis;
    if (doc_.contains("analysis")) {
      const json& an = doc_["analysis"];
      expect_object(an, "analysis");
      check_keys(an, "analysis", {"control", "tolerance", "max_iterations", "cutback", "max_cutbacks", "output", "monitor"});
      if (an.contains("control")) read_control(an["control"], "analysis.control");
      if (auto tol = optional_number(an, "tolerance", "analysis")) {
        if (!(*tol > 0.0 && *tol < 1.0)) fail("analysis.tolerance", "must lie between 0 and 1");
        a.tolerance = *tol;
      }
      if (an.contains("max_iterations")) a.max_iterations = static_cast<int>(bounded_integer(an["max_iterations"], "analysis.max_iterations", 1, 100000));
      if (an.contains("cutback")) a.cutback = boolean(an["cutback"], "analysis.cutback");
      if (an.contains("max_cutbacks")) a.max_cutbacks = static_cast<int>(bounded_integer(an["max_cutbacks"], "analysis.max_cutbacks", 0, 60));
      if (an.contains("output")) read_output(an["output"], "analysis.output");
      if (an.contains("monitor")) {
        expect_array(an["monitor"], "analysis.monitor");
        for (size_t k = 0; k < an["monitor"].size(); ++k) a.monitor.push_back(node_ref(an["monitor"][k], child("analysis.monitor", k)));
      }
    }
    if (!doc_.contains("analysis") || !doc_["analysis"].contains("monitor")) {
      // The nodes named by a load or a prescribed displacement; a member's load (lumped at every
      // node of it) adds none — a uniformly loaded beam of 1,000 elements would otherwise put
      // 3,000 columns in steps.csv — unless nothing else is named: then its middle node.
      for (int k = 0; k < model_.node_count(); ++k) {
        bool named = nodally_loaded_.count(k) > 0;
        for (int dof = 0; dof < dofs_per_node; ++dof) named = named || model_.prescribed(dofs_per_node * k + dof) != 0.0;
        if (named) a.monitor.push_back(k);
      }
      if (a.monitor.empty()) {
        for (const int middle : loaded_member_middles_)
          if (std::find(a.monitor.begin(), a.monitor.end(), middle) == a.monitor.end()) a.monitor.push_back(middle);
      }
    }
  }

  void read_control(const json& c, const std::string& path) {
    expect_object(c, path);
    if (!c.contains("type")) fail(child(path, "type"), "missing (required: \"load\", \"displacement\" or \"arc-length\")");
    const std::string type = string(c["type"], child(path, "type"));
    Control& control = model_.analysis.control;
    if (type == "load") {
      check_keys(c, path, {"type", "steps", "path"});
      control.type = ControlType::load;
      if (c.contains("path")) {
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
    } else if (type == "displacement") {
      check_keys(c, path, {"type", "steps", "node", "dof", "target"});
      control.type = ControlType::displacement;
      control.node = required_node(c, path);
      if (!c.contains("dof")) fail(child(path, "dof"), "missing (required)");
      control.dof = dof_from_name(string(c["dof"], child(path, "dof")), child(path, "dof"));
      control.target = required_number(c, "target", path);
      if (control.target == 0.0) fail(child(path, "target"), "must not be zero");
      if (model_.constrained[dofs_per_node * control.node + control.dof])
        fail(child(path, "dof"), std::string("the controlled dof ") + dof_name(control.dof) + " of node " + std::to_string(model_.nodes[control.node].id) + " is fixed or prescribed");
    } else if (type == "arc-length") {
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
      if (c.contains("until")) {
        const std::string upath = child(path, "until");
        const json& u = c["until"];
        expect_object(u, upath);
        if (u.contains("load_factor")) {
          check_keys(u, upath, {"load_factor"});
          control.until = Control::Until::load_factor;
          control.until_value = required_number(u, "load_factor", upath);
          if (control.until_value == 0.0) fail(child(upath, "load_factor"), "must not be zero (the path starts there)");
        } else {
          check_keys(u, upath, {"node", "dof", "value"});
          control.until = Control::Until::displacement;
          control.until_node = required_node(u, upath);
          if (!u.contains("dof")) fail(child(upath, "dof"), "missing (required, or give \"load_factor\")");
          control.until_dof = dof_from_name(string(u["dof"], child(upath, "dof")), child(upath, "dof"));
          control.until_value = required_number(u, "value", upath);
          if (model_.constrained[dofs_per_node * control.until_node + control.until_dof])
            fail(child(upath, "dof"), std::string("the dof ") + dof_name(control.until_dof) + " of node " + std::to_string(model_.nodes[control.until_node].id) + " is fixed or prescribed");
          if (control.until_value == 0.0) fail(child(upath, "value"), "must not be zero (the path starts there)");
        }
      }
    } else {
      fail(child(path, "type"), "unknown control " + quote_text(type) + " (expected \"load\", \"displacement\" or \"arc-length\")");
    }
    if (c.contains("steps")) control.steps = static_cast<int>(bounded_integer(c["steps"], child(path, "steps"), 1, max_steps));
  }

  /// The steps whose full state the output selection keeps (in memory until the run ends, then in
  /// results.json) must fit: a step count meant as 100 and typed as 100,000 on a large model would
  /// otherwise run for hours and then run out of memory. Load and displacement control only,
  /// whose step count is known (arc-length's max_steps is a bound, not a count).
  void check_kept_states() const {
    const AnalysisSettings& a = model_.analysis;
    if (a.control.type == ControlType::arc_length) return;
    const double legs = a.control.path.empty() ? 1.0 : static_cast<double>(a.control.path.size());  // from λ = 0 to each point
    const double steps = static_cast<double>(a.control.steps) * legs;
    const double kept = a.output.kind == OutputSelection::Kind::last ? 1.0
                        : a.output.kind == OutputSelection::Kind::every ? std::ceil(steps / a.output.every) + 1.0
                                                                         : steps;
    // Per kept step: displacements and reactions (3 per node), element forces (4 per element), 8 bytes each.
    const double bytes = kept * 8.0 * (6.0 * model_.node_count() + 4.0 * static_cast<double>(model_.elements.size()));
    if (bytes > max_kept_state_bytes) {
      std::ostringstream os;
      os.precision(3);
      os << "keeping the full state of " << static_cast<long long>(kept) << " steps of " << model_.elements.size()
         << " elements takes ~" << bytes / 1e9 << " GB of memory, and more in results.json (at most "
         << max_kept_state_bytes / 1e9 << " GB): give \"output\" a step interval k (every k-th step) or \"last\", or fewer steps";
      fail("analysis.output", os.str());
    }
  }

  void read_output(const json& o, const std::string& path) {
    OutputSelection& out = model_.analysis.output;
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

  const json& doc_;
  Model model_;
  std::map<std::string, Material> materials_;
  std::map<std::string, Section> sections_;
  std::set<int> connected_members_;  ///< members with a moment release or an end spring ("release", "end_springs")
  struct MemberLoad {
    int start, end;  ///< an element's nodes
    double fx, fy;   ///< the share of its distributed load each of them takes
  };
  std::vector<MemberLoad> member_loads_;  ///< members' "load", element by element
  std::set<int> nodally_loaded_;          ///< nodes a "loads" entry names with a nonzero value
  std::vector<int> loaded_member_middles_;  ///< per member with a "load" (in file order): its middle node (a generated one; none for 1 division)
  std::unordered_map<int, int> ids_;
};

/// Line and column (1-based) of a byte offset.
std::pair<size_t, size_t> line_column(const std::string& text, size_t offset) {
  size_t line = 1, column = 1;
  for (size_t k = 0; k < std::min(offset, text.size()); ++k) {
    if (text[k] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return {line, column};
}

}  // namespace

Model read_model(const json& document) { return Reader(document).read(); }

Model read_model_text(const std::string& text) {
  json document;
  try {
    document = json::parse(text);
  } catch (const json::parse_error& e) {
    // nlohmann's byte is one past the offending character; report the character itself.
    const auto [line, column] = line_column(text, e.byte > 0 ? e.byte - 1 : 0);
    std::string reason = e.what();
    const auto colon = reason.find("syntax error");
    if (colon != std::string::npos) reason = reason.substr(colon);
    fail("", "invalid JSON at line " + std::to_string(line) + ", column " + std::to_string(column) + ": " + reason);
  } catch (const json::exception& e) {  // a number beyond a double's range (out_of_range 406)
    std::string reason = e.what();
    const auto bracket = reason.find("] ");
    if (bracket != std::string::npos) reason = reason.substr(bracket + 2);
    fail("", "invalid JSON: " + reason + " (beyond a double's range)");
  }
  return read_model(document);
}

Model read_model_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail("", "cannot open the file");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) fail("", "cannot read the file");
  return read_model_text(buffer.str());
}

}  // namespace tsm::io
