#pragma once
// The rounding floor of the assembled internal forces at a state: the error that rounding leaves
// in them (ε times the coordinates and forces each element's arithmetic involves, taken as
// independent), under which no residual can fall. Newton holds a stagnating residual against it
// (solver/convergence). Numbers only: what they mean for a user is solver/diagnosis's.

#include <Eigen/Core>
#include <array>

#include "tsmframe/contact/contact_set.hpp"

namespace tsm::assembly {

/// Estimated rounding error of the assembled internal forces, per kind (2-norm over dofs):
/// the floor under any residual at a state.
struct RoundingFloor {
  double force = 0.0;
  double moment = 0.0;
  /// The active contact whose force Y rounds the most (its contact node; −1 where none is
  /// active): ±`contact_force`, its compliance `compliance` at the point, `at_edge` where that is
  /// the compliance floor near a beam node (the contact's `edge`), `at_cap` where it is the floor
  /// its stiffness cap sets (max_stiffness_ratio).
  int contact_node = -1;
  double contact_force = 0.0;
  double compliance = 0.0;
  bool at_edge = false;
  bool at_cap = false;
  bool uncapped = false;  ///< its node is held by no element (a rigid pusher): no stiffness cap
  /// All active contacts' share of `force` (the root of their squared terms) and how many.
  double contacts_force = 0.0;
  int contacts = 0;
};

/// An active contact element's share of the floor: its squared terms per kind (forces over its
/// dofs, moments) and its point forces' rounding (the largest: its node, what sets its
/// compliance there).
struct ContactRounding {
  double force_squared = 0.0, moment_squared = 0.0;
  double points_squared = 0.0;  ///< the points' share of force_squared
  int node = -1;            ///< the point whose Y rounds the most: its node
  double y_floor = 0.0;     ///< the rounding of its Y
  double compliance = 0.0;  ///< c at the point
  bool at_edge = false, at_cap = false, uncapped = false;  ///< as RoundingFloor's
};
/// `d`: the contact element's displacements (contact_dofs); `rotation`: its chord's rotation at the state.
ContactRounding contact_rounding(const contact::ActiveContact& contact, const Eigen::VectorXd& d, double rotation);

/// The floor from the plain elements' squared sums per kind and the active contacts' shares.
RoundingFloor rounding_floor(std::array<double, 2> elements_squared, const std::vector<contact::ActiveContact>& contacts,
                             const std::vector<ContactRounding>& shares);

}  // namespace tsm::assembly
