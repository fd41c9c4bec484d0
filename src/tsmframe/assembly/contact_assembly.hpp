#pragma once
// A contact element in the global system: its nine dofs (the beam element's two nodes, then the
// contact node), its displacements gathered, and its point load seen from the free equations
// (what Newton's release look-ahead needs). The element loop (global_system) adds the element's
// forces, the symmetric part of its tangent to the node blocks and its sliding term as a rank-one
// term beside them.

#include <Eigen/Core>
#include <array>
#include <vector>

#include "tsmframe/assembly/dof_map.hpp"
#include "tsmframe/contact/contact_set.hpp"
#include "tsmframe/model/model.hpp"

namespace tsm::assembly {

/// An active contact's point load seen from the free equations (contact_directions): Y acts as
/// Y · u on its three nodes, and its stiffness part is stiffness · u uᵀ.
struct ContactDirection {
  std::array<int, 9> equation{};  ///< free equation of each entry of u, −1 where constrained
  Eigen::Matrix<double, 9, 1> u;
  double stiffness = 0.0;  ///< 1/c
  double Y = 0.0;
};

/// A contact element's dofs: the beam element's two nodes, then the contact node.
std::array<int, 9> contact_dofs(const Element& element, int node);

/// The displacements of the given dofs.
template <size_t N>
Eigen::Matrix<double, N, 1> gather(const Eigen::VectorXd& displacements, const std::array<int, N>& dofs) {
  Eigen::Matrix<double, N, 1> d;
  for (size_t a = 0; a < N; ++a) d[a] = displacements[dofs[a]];
  return d;
}

/// Each active contact's (in `contacts`' order) point load direction and stiffness at
/// `displacements` (chord rotations of that state's evaluation).
std::vector<ContactDirection> contact_directions(const Model& model, const DofMap& dofs,
                                                 const Eigen::VectorXd& displacements, const std::vector<double>& rotations,
                                                 const std::vector<contact::ActiveContact>& contacts);

}  // namespace tsm::assembly
