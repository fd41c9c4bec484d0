#pragma once
// A contact element in the global system: its dofs (the beam element's two nodes, then each
// contact point's node), its displacements gathered, and its points' loads seen from the free
// equations (what Newton's release look-ahead needs). The element loop (global_system) adds the
// element's forces, the symmetric part of its tangent to the node blocks and each point's
// sliding term as a rank-one term beside them.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

#include "tsmframe/assembly/dof_map.hpp"
#include "tsmframe/contact/active_contact.hpp"
#include "tsmframe/contact/contact_set.hpp"
#include "tsmframe/model/model.hpp"
#include "tsmframe/model/nodal_frames.hpp"

namespace tsm::assembly {

/// What the assembly adds of a one-point contact's response (GlobalSystem::add_contact), kept per
/// contact from one evaluation to the next: at the same displacements (a contact change) a
/// contact whose element, offset (its side) and normal stay gives the same response — its
/// chord's rotation, continued from the one it gave, within an ulp — and only the contacts that
/// changed are formed again.
struct KeptPointResponse {
  std::uint64_t evaluation = 0;  ///< the Evaluation::id it was formed in or carried into (0: none)
  int element = -1;
  double offset = 0.0;
  ContactNormal normal = ContactNormal::chord;
  element::Chord chord;
  double alpha = 0.0, force_per_Y = 1.0;
  contact::Vector4 forces;
  contact::Vector9 nodal_forces, sliding_u, sliding_v;
  std::array<Eigen::Matrix3d, 6> blocks;  ///< symmetric_tangent's node blocks (p, q ≥ p) in that order
  /// Formed for `contact` (one point, not a vertex's second) in the evaluation before `id`.
  bool stands_for(const contact::ActiveContact& contact, std::uint64_t id) const {
    const contact::ContactElementData& data = contact.data.front();
    return evaluation + 1 == id && element == contact.element && offset == data.offset && normal == data.normal;
  }
};
/// `response` (of `contact`'s element, formed in evaluation `id`) kept.
void keep(const contact::ActiveContact& contact, const contact::ContactResponse& response, std::uint64_t id,
          KeptPointResponse& kept);

/// A contact point's load seen from the free equations (contact_directions): Y acts as Y · u on
/// its element's nodes, and where it is its element's only point its stiffness part is
/// stiffness · u uᵀ (with several, the points' stiffness is C⁻¹, coupled: `stiffness` is its
/// diagonal entry).
struct ContactDirection {
  std::vector<int> equation;  ///< free equation of each entry of u, −1 where constrained
  Eigen::VectorXd u;
  double stiffness = 0.0;  ///< 1/c (the diagonal entry of C⁻¹ where points share an element)
  double Y = 0.0;
  int element = 0;                    ///< its contact element: the index in the contacts given
  Eigen::RowVectorXd stiffness_row;   ///< its row of the element's point stiffness C⁻¹ (one entry per point)
};

/// A contact element's dofs: the beam element's two nodes, then each point's node (into `dofs`:
/// its storage reused).
std::vector<int> contact_dofs(const Element& element, const contact::ActiveContact& contact);
void contact_dofs(const Element& element, const contact::ActiveContact& contact, std::vector<int>& dofs);

/// The displacements of the given dofs (into `values`: its storage reused).
Eigen::VectorXd gather(const Eigen::VectorXd& displacements, const std::vector<int>& dofs);
void gather(const Eigen::VectorXd& displacements, const std::vector<int>& dofs, Eigen::VectorXd& values);

/// A contact element's response at `displacements` (its chord's rotation before: `previous_rotations`),
/// into `response` (its storage reused): a function of the element's own dofs, safe to form on
/// several threads at once.
void contact_element_response(const Model& model, const contact::ActiveContact& contact, const Eigen::VectorXd& displacements,
                      const std::vector<double>& previous_rotations, bool with_tangent, contact::MultiPointResponse& response);
/// The same for a contact of one point, in the three-node element's fixed-size form.
void contact_element_response(const Model& model, const contact::ActiveContact& contact, const Eigen::VectorXd& displacements,
                      const std::vector<double>& previous_rotations, bool with_tangent, contact::ContactResponse& response);

/// Each active contact point's (in `contacts`' order, points in order) load direction and
/// stiffness at `displacements` (chord rotations of that state's evaluation).
/// At a skew roller u is in its frame (NodalFrames).
std::vector<ContactDirection> contact_directions(const Model& model, const DofMap& dofs, const NodalFrames& frames,
                                                 const Eigen::VectorXd& displacements, const std::vector<double>& rotations,
                                                 const std::vector<contact::ActiveContact>& contacts);

}  // namespace tsm::assembly
