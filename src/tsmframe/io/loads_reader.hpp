#pragma once
// What a model file applies (docs/format.md): nodal "loads" (follower ones included),
// "prescribed" displacements, and the "stages" that apply them in turn (each with its loads,
// prescribed displacements, control and output).

#include <Eigen/Core>
#include <functional>
#include <nlohmann/json_fwd.hpp>
#include <set>
#include <string>
#include <vector>

#include "tsmframe/io/analysis_reader.hpp"
#include "tsmframe/model/model.hpp"

namespace tsm::io {

/// Reads loads, prescribed displacements and stages against a meshed model (its nodes, supports
/// and hinges known), and keeps the nodes they name (steps.csv's default monitor). Throws
/// InputError.
class LoadsReader {
 public:
  /// The node at a member's station (a point load's "member" and "at"; mesh.hpp), −1: none.
  using StationResolver = std::function<int(int member, double at)>;

  LoadsReader(const Model& model, NodeResolver node, StationResolver station)
      : model_(model), node_(std::move(node)), station_(std::move(station)) {}

  /// A "loads" array at `path`: nodal forces and moments into `load` (per dof), follower forces
  /// into `followers`.
  void read_loads(const nlohmann::json& loads, const std::string& path, Eigen::VectorXd& load,
                  std::vector<FollowerForce>& followers);
  /// A "prescribed" array at `path`: each entry's dofs and values (with `increments`, an entry
  /// may say its values are increments on where the dofs stand: "increment": true).
  std::vector<PrescribedTarget> read_prescribed(const nlohmann::json& prescribed, const std::string& path, bool increments);
  /// A "stages" array: each stage's loads, prescribed displacements, control (its dof free of
  /// the supports and of this and earlier stages' prescribed dofs) and output (else `output`).
  /// `contact_entries`: the first contact (Model::contacts) of each "contacts" entry, and their
  /// count last — a stage's "contacts" names entries.
  std::vector<Stage> read_stages(const nlohmann::json& stages, const OutputSelection& output,
                                 const std::vector<int>& contact_entries);

  /// Nodes a load entry names with a nonzero value.
  const std::set<int>& loaded_nodes() const { return loaded_; }
  /// Nodes a prescribed entry names.
  const std::set<int>& prescribed_nodes() const { return prescribed_; }

 private:
  FollowerForce follower_force(const std::string& path, int node, const Eigen::Vector2d& force);
  int load_node(const nlohmann::json& l, const std::string& path) const;

  const Model& model_;
  NodeResolver node_;
  StationResolver station_;
  std::vector<char> hinge_, turned_;  ///< hinge_nodes and turned_nodes, once a load asks
  std::set<int> loaded_, prescribed_;
};

/// The stations of each member's point loads ("member" and "at" in the loads of `document` and
/// of its stages), checked, ascending and distinct, per member (of `members`). A load entry not
/// well formed enough to tell is left to read_loads.
std::vector<std::vector<double>> member_stations(const nlohmann::json& document, size_t members);

/// With "stages", the loads, prescribed displacements and control belong to the stages: refuses
/// them at the document's top level.
void refuse_unstaged_keys(const nlohmann::json& document);

}  // namespace tsm::io
