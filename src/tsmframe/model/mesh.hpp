#pragma once
// Members made into the model's nodes and elements (docs/format.md, "A member"): each divided into
// equal elements along its chord or a circular arc, the interior nodes numbered after the largest
// id; its distributed load lumped half to each end of every element; and what follows from the
// mesh — rotations no element end holds fixed, the nodes steps.csv shows by default.

#include <Eigen/Core>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "tsmframe/element/force_law.hpp"
#include "tsmframe/model/model.hpp"

namespace tsm {

/// A circular arc a member follows from its first node to its last: `sweep` radians about
/// `centre` (counter-clockwise positive; ±2π: a closed ring, first node = last node).
struct Arc {
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  double sweep = 0.0;
};

/// A member as the input describes it, each value already read and checked on its own; meshing
/// checks what depends on the geometry (MeshError).
struct MemberInput {
  int from = 0, to = 0;  ///< node indices
  long divisions = 1;
  std::optional<Arc> arc;  ///< none: straight
  BeamTheory theory = BeamTheory::euler_bernoulli;
  element::SectionStiffness section;
  bool release_start = false, release_end = false;        ///< hinges at its ends
  double flexibility_from = 0.0, flexibility_to = 0.0;    ///< end springs' 1/k (MemberExtras), 0: rigid
  Eigen::Vector2d load = Eigen::Vector2d::Zero();         ///< distributed, per unit length, global x and y
  double pressure = 0.0;                                  ///< follower load (MemberExtras)
  /// An elastic (Winkler) foundation's stiffness per unit length (0: none): each element gets
  /// springs of k l/2 at its ends along its normal as drawn (Model::springs).
  double foundation = 0.0;
  /// Where point loads act along it (loads' "member" and "at"): fractions of its length (of its
  /// sweep, on an arc) in (0, 1), ascending; each is a node (a division point, or one added
  /// between, splitting that element in two).
  std::vector<double> stations;
};

/// A member whose geometry cannot be meshed. `value` names the member's value at fault, for the
/// reader to give its place in the input.
class MeshError : public std::runtime_error {
 public:
  enum class Value { member, arc, arc_centre, arc_sweep };
  MeshError(Value value, const std::string& reason) : std::runtime_error(reason), value_(value) {}
  Value value() const { return value_; }

 private:
  Value value_;
};

/// Meshes members into a model one after another — a member may name a node an earlier member
/// generated — and then lumps their distributed loads.
class MemberMesh {
 public:
  /// The model holds the input's nodes (and its size) and no element yet.
  explicit MemberMesh(Model& model);
  /// Appends the member's interior nodes and elements; member index: the members before it.
  /// Throws MeshError.
  void add(const MemberInput& member);
  /// After the last member: storage trimmed, the dof arrays sized (all dofs free, unloaded,
  /// nothing prescribed) and the members' distributed loads lumped into reference_load.
  void finish();
  /// Per member with a distributed load or pressure, in member order: its middle node (a
  /// generated one; none for a single division).
  const std::vector<int>& loaded_middles() const { return loaded_middles_; }
  /// The node at a station of a member (MemberInput::stations), or −1 if it has none there.
  int station_node(int member, double fraction) const;

 private:
  /// An element's share of its member's distributed load, at each of its two nodes.
  struct ElementLoad {
    int start, end;
    double fx, fy;
  };
  std::vector<Eigen::Vector2d> interior_points(const MemberInput& member) const;
  /// The member's point at a fraction of its length (its sweep, on an arc).
  Eigen::Vector2d point_at(const MemberInput& member, double fraction) const;
  /// Its interior nodes' points and fractions in order: the division points and the stations
  /// between them; each station's node index offset (into this list) in `station_at`.
  struct Interior {
    std::vector<Eigen::Vector2d> points;
    std::vector<long> division;                      ///< per point: its division d, 0 for a station's
    std::vector<std::pair<double, int>> station_at;  ///< (fraction, index in points; −1: `to`, −2: `from`)
  };
  Interior interior(const MemberInput& member) const;

  Model& model_;
  int next_id_;
  std::vector<ElementLoad> element_loads_;
  std::vector<int> loaded_middles_;
  std::vector<std::vector<std::pair<double, int>>> station_nodes_;  ///< per member: (fraction, node index)
};

/// Fixes the rotation of every node no element end turns with: a node no element holds (a rigid
/// pusher), and a hinge where every element end is released (hinge_nodes).
void fix_free_rotations(Model& model);

/// The nodes steps.csv shows when the input names none: those a nodal load (`nodally_loaded`,
/// node indices) or a prescribed displacement names; a member's distributed load, lumped at all
/// its nodes, adds none — unless nothing else is named: then the members' `loaded_middles`.
std::vector<int> default_monitor(const Model& model, const std::set<int>& nodally_loaded,
                                 const std::vector<int>& loaded_middles);

}  // namespace tsm
