#include "tsmframe/model/mesh.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <numbers>

#include "tsmframe/model/hinges.hpp"

namespace tsm {
namespace {

constexpr double two_pi = 2.0 * std::numbers::pi;

/// Shortest text that reads back to the same double, as the results print numbers.
std::string shortest_text(double x) {
  if (x == 0.0) return "0";
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, x);
  return std::string(buffer, result.ptr);
}

/// The arc's points at angles start + sweep · d / divisions, d = 1 … divisions − 1, after
/// checking that it runs from `a` to `b` (a closed ring: a = b and a full turn).
std::vector<Eigen::Vector2d> arc_points(const Arc& arc, const Eigen::Vector2d& a, const Eigen::Vector2d& b, bool closed,
                                        long divisions, double model_size) {
  using Value = MeshError::Value;
  const Eigen::Vector2d& centre = arc.centre;
  const double radius = (a - centre).norm();
  if (radius <= 1e-12 * model_size) throw MeshError(Value::arc_centre, "the centre coincides with the start node");
  if (std::abs((b - centre).norm() - radius) > 1e-6 * radius)
    throw MeshError(Value::arc_centre, "the start and end nodes are not on one circle about the centre");
  const double start = std::atan2(a.y() - centre.y(), a.x() - centre.x());
  const Eigen::Vector2d reached = centre + radius * Eigen::Vector2d(std::cos(start + arc.sweep), std::sin(start + arc.sweep));
  if ((reached - b).norm() > 1e-6 * radius) {
    // Name the sweeps that do reach it: the short way round and the long one (a closed ring: ±2π).
    double to_end = std::atan2(b.y() - centre.y(), b.x() - centre.x()) - start;
    to_end = std::remainder(to_end, two_pi);
    const double other = to_end > 0.0 ? to_end - two_pi : to_end + two_pi;
    throw MeshError(Value::arc_sweep, "the sweep from the start node does not end at the end node (" + shortest_text(to_end) +
                                          " or " + shortest_text(other) + " does)");
  }
  if (closed != (std::abs(std::abs(arc.sweep) - two_pi) < 1e-9))
    throw MeshError(Value::arc, "a full circle must start and end at the same node");
  std::vector<Eigen::Vector2d> points;
  for (long d = 1; d < divisions; ++d) {
    const double angle = start + arc.sweep * static_cast<double>(d) / divisions;
    points.push_back(centre + radius * Eigen::Vector2d(std::cos(angle), std::sin(angle)));
  }
  return points;
}

}  // namespace

MemberMesh::MemberMesh(Model& model) : model_(model), next_id_(std::numeric_limits<int>::min()) {
  for (const Node& n : model_.nodes) next_id_ = std::max(next_id_, n.id + 1);
}

std::vector<Eigen::Vector2d> MemberMesh::interior_points(const MemberInput& member) const {
  const Eigen::Vector2d a = model_.nodes[member.from].position, b = model_.nodes[member.to].position;
  if (member.arc) return arc_points(*member.arc, a, b, member.from == member.to, member.divisions, model_.size);
  if (member.from == member.to || (b - a).norm() <= 1e-12 * model_.size)
    throw MeshError(MeshError::Value::member, "zero-length member (from and to are the same point)");
  std::vector<Eigen::Vector2d> points;
  for (long d = 1; d < member.divisions; ++d) points.push_back(a + (b - a) * (static_cast<double>(d) / member.divisions));
  return points;
}

Eigen::Vector2d MemberMesh::point_at(const MemberInput& member, double fraction) const {
  const Eigen::Vector2d a = model_.nodes[member.from].position, b = model_.nodes[member.to].position;
  if (!member.arc) return a + (b - a) * fraction;
  const Eigen::Vector2d& centre = member.arc->centre;
  const double start = std::atan2(a.y() - centre.y(), a.x() - centre.x()), angle = start + member.arc->sweep * fraction;
  return centre + (a - centre).norm() * Eigen::Vector2d(std::cos(angle), std::sin(angle));
}

MemberMesh::Interior MemberMesh::interior(const MemberInput& member) const {
  constexpr double snap = 1e-6;  // a station this close to a division point (of the length) is that point
  const std::vector<Eigen::Vector2d> divisions = interior_points(member);
  const std::vector<double>& stations = member.stations;
  Interior in;
  size_t s = 0;
  for (; s < stations.size() && stations[s] <= snap; ++s) in.station_at.push_back({stations[s], -2});
  for (long d = 1; d <= member.divisions; ++d) {
    const double f = static_cast<double>(d) / member.divisions;
    for (; s < stations.size() && stations[s] < f - snap; ++s) {  // a node of its own, between division points
      in.station_at.push_back({stations[s], static_cast<int>(in.points.size())});
      in.points.push_back(point_at(member, stations[s]));
      in.division.push_back(0);
    }
    for (; s < stations.size() && stations[s] <= f + snap; ++s)
      in.station_at.push_back({stations[s], d < member.divisions ? static_cast<int>(in.points.size()) : -1});
    if (d == member.divisions) break;
    in.points.push_back(divisions[d - 1]);
    in.division.push_back(d);
  }
  return in;
}

int MemberMesh::station_node(int member, double fraction) const {
  if (member < 0 || member >= static_cast<int>(station_nodes_.size())) return -1;
  for (const auto& [f, node] : station_nodes_[member])
    if (f == fraction) return node;
  return -1;
}

void MemberMesh::add(const MemberInput& member) {
  const int index = model_.member_count;
  if (member.pressure != 0.0 || member.flexibility_from > 0.0 || member.flexibility_to > 0.0) {
    model_.member_extras.resize(index + 1);
    model_.member_extras[index] = {member.pressure, member.flexibility_from, member.flexibility_to};
  }
  const Interior interior = this->interior(member);
  const bool loaded = member.load.x() != 0.0 || member.load.y() != 0.0 || member.pressure != 0.0;
  const long elements = static_cast<long>(interior.points.size()) + 1;
  const int first_node = model_.node_count();
  int previous = member.from;
  for (long q = 1; q <= elements; ++q) {
    int current = member.to;
    if (q < elements) {
      if (next_id_ == std::numeric_limits<int>::max()) throw MeshError(MeshError::Value::member, "node ids overflow");
      model_.nodes.push_back({next_id_++, interior.points[q - 1]});
      current = model_.node_count() - 1;
    }
    const long d = q < elements ? interior.division[q - 1] : member.divisions;  // 0: a station's node
    Element e;
    e.id = static_cast<int>(model_.elements.size()) + 1;
    e.start = previous;
    e.end = current;
    e.member = index;
    e.theory = member.theory;
    e.release_start = member.release_start && q == 1;
    e.release_end = member.release_end && q == elements;
    e.member_start = q == 1;
    e.member_end = q == elements;
    e.section = member.section;
    model_.elements.push_back(e);
    if (member.load.x() != 0.0 || member.load.y() != 0.0) {  // per unit length along the drawn element, half to each end
      const double length = model_.drawn_length(e);
      element_loads_.push_back({e.start, e.end, member.load.x() * length / 2.0, member.load.y() * length / 2.0});
    }
    if (member.foundation > 0.0) {  // k per unit length along the drawn element, half to each end, along its normal
      const Eigen::Vector2d chord = model_.nodes[e.end].position - model_.nodes[e.start].position;
      const Eigen::Vector2d normal = Eigen::Vector2d(-chord.y(), chord.x()).normalized();
      const double half = member.foundation * chord.norm() / 2.0;
      for (const int node : {e.start, e.end}) model_.springs.push_back({node, NodalSpring::Kind::translation, normal, half});
    }
    if (loaded && member.divisions >= 2 && d == member.divisions / 2) loaded_middles_.push_back(current);
    previous = current;
  }
  station_nodes_.resize(index + 1);
  for (const auto& [fraction, at] : interior.station_at)
    station_nodes_[index].push_back({fraction, at == -2 ? member.from : at == -1 ? member.to : first_node + at});
  ++model_.member_count;
}

void MemberMesh::finish() {
  if (!model_.member_extras.empty()) model_.member_extras.resize(model_.member_count);
  model_.nodes.shrink_to_fit();  // no growth slack kept through the analysis
  model_.elements.shrink_to_fit();
  model_.constrained.assign(model_.dof_count(), false);
  model_.reference_load = Eigen::VectorXd::Zero(model_.dof_count());
  model_.reference_prescribed = Eigen::VectorXd::Zero(model_.dof_count());
  for (const ElementLoad& l : element_loads_) {
    model_.reference_load[dofs_per_node * l.start + ux] += l.fx;
    model_.reference_load[dofs_per_node * l.start + uy] += l.fy;
    model_.reference_load[dofs_per_node * l.end + ux] += l.fx;
    model_.reference_load[dofs_per_node * l.end + uy] += l.fy;
  }
}

void fix_free_rotations(Model& model) {
  const std::vector<char> turned = turned_nodes(model);
  for (int k = 0; k < model.node_count(); ++k)
    if (!turned[k]) model.constrained[dofs_per_node * k + rz] = true;
}

std::vector<int> default_monitor(const Model& model, const std::set<int>& nodally_loaded,
                                 const std::vector<int>& loaded_middles) {
  std::vector<int> monitor;
  for (int k = 0; k < model.node_count(); ++k) {
    bool named = nodally_loaded.count(k) > 0;
    for (int dof = 0; dof < dofs_per_node; ++dof) named = named || model.prescribed(dofs_per_node * k + dof) != 0.0;
    if (named) monitor.push_back(k);
  }
  if (!monitor.empty()) return monitor;
  for (const int middle : loaded_middles)
    if (std::find(monitor.begin(), monitor.end(), middle) == monitor.end()) monitor.push_back(middle);
  return monitor;
}

}  // namespace tsm
