#pragma once
// Kinematic check of a model before any solve. Beam elements are rigid-jointed and carry
// axial force and bending, so the only mechanisms are rigid-body motions of connected parts
// that the supports do not stop: a node that no element holds, or a part whose fixed dofs
// leave a translation or a rotation free.

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "tsmframe/model/model.hpp"
#include "tsmframe/model/nodal_frames.hpp"

namespace tsm {

/// A sentence naming the free motion and a node on it, or nothing if the model is stable. Held
/// contacts resting on a part as drawn (model/resting_contact) count as supports along their
/// normal unless `resting_contacts_hold` is false.
std::optional<std::string> find_mechanism(const Model& model, bool resting_contacts_hold = true);
/// Whether find_mechanism finds one, without the sentence (which looks at every contact against
/// every element for one that plainly does not rest).
bool is_mechanism(const Model& model, bool resting_contacts_hold = true);

/// find_mechanism where the analysis starts: the supports and the first stage's prescribed dofs
/// (later stages only hold more). `model.constrained` is marked while it looks and restored.
std::optional<std::string> starting_mechanism(Model& model);

/// A rigid-body motion a connected part is free to make against what holds it.
struct FreeMotion {
  int node = -1;       ///< the part's first node (index)
  int part_nodes = 0;  ///< how many nodes the part has
  enum class Kind { translation, rotation } kind = Kind::translation;
  Eigen::Vector2d direction = Eigen::Vector2d::UnitX();  ///< a translation's, unit
  Eigen::Vector2d pole = Eigen::Vector2d::Zero();        ///< the point a rotation turns about
};

/// "the part holding node 1 and the 8 nodes joined to it"
std::string part_text(const Model& model, const FreeMotion& motion);
/// "rotate about (0, 0)", "move along x", "move in the direction 0.5 rad from x"
std::string motion_text(const FreeMotion& motion);

/// The rigid-body motions supports and springs leave free where the nodes stand at any state:
/// the supports' lines of action can come to meet as the structure deforms (a beam on a pin and
/// a roller bent into a full circle, its ends on one point, may turn about the pin). The parts
/// and what holds each are found once. Contacts hold nothing here: ask where none is active.
class SupportedParts {
 public:
  explicit SupportedParts(const Model& model);
  /// The first part free to move at `displacements` (global, every dof) whose loads and reactions
  /// (`internal_forces`: the internal force at every dof, global, at that equilibrium) do no work
  /// along its motion to second order: along it the tangent stiffness vanishes, so that its
  /// inertia tells nothing of the stability (neutral equilibrium). A pendulum's rotation, which its
  /// load stiffens or softens, is none.
  std::optional<FreeMotion> neutral_motion(const Eigen::VectorXd& displacements,
                                           const Eigen::VectorXd& internal_forces) const;

 private:
  const Model& model_;
  NodalFrames frames_;
  std::vector<char> hinge_;
  std::vector<std::vector<int>> parts_;    ///< the nodes elements join, per part
  std::vector<std::vector<int>> springs_;  ///< per part: the springs holding it (Model::springs)
};

}  // namespace tsm
