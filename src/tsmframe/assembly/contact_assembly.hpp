#pragma once
// A contact element in the global system: its dofs (the beam element's two nodes, then each
// contact point's node), its displacements gathered, and its points' loads seen from the free
// equations (what Newton's release look-ahead needs). The element loop (global_system) adds the
// element's forces, the symmetric part of its tangent to the node blocks and each point's
// sliding term as a rank-one term beside them.

#include <Eigen/Core>
#include <vector>

#include "tsmframe/assembly/dof_map.hpp"
#include "tsmframe/contact/active_contact.hpp"
#include "tsmframe/contact/contact_set.hpp"
#include "tsmframe/model/model.hpp"
#include "tsmframe/model/nodal_frames.hpp"

namespace tsm::assembly {

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
