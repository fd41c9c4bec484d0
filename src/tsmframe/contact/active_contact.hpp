#pragma once
// The contact element of one element at a state: the beam element with every contact point on
// it (issue 27), what assembly evaluates. One point is the paper's three-node element in its
// contact's frame (contact_response.hpp, Eq. 6–9 exactly); several are the k-point element in
// their frame — the chord's (multi_point_element.hpp), with the force of each point that asks for
// it along the bent beam's normal (multi_point_deflected_normal.hpp), or the cantilever's
// (multi_point_cantilever_frame.hpp). Either way the response has the k-point form.

#include <vector>

#include <Eigen/Core>

#include "tsmframe/contact/contact_element.hpp"
#include "tsmframe/contact/multi_point_element.hpp"

namespace tsm::contact {

/// A contact point on the element: the node of contact `contact`.
struct ActivePoint {
  int contact = -1;     ///< index of the contact (model order)
  bool vertex = false;  ///< the second element of a vertex (ContactState::vertex)
  int node = 0;
};

/// An element with the contact points on it (k ≥ 1), in the order their contacts come.
struct ActiveContact {
  int element = 0;
  std::vector<ActivePoint> points;
  /// Per point, the three-node element it would make alone (its node as drawn, offset, floors,
  /// frame); the k-point element takes the beam's data from the first and each point's own.
  std::vector<ContactElementData> data;
  int size() const { return static_cast<int>(points.size()); }
};

/// The k-point element's data from the points' (k ≥ 2; all in one frame). Points of different
/// contacts share one law: the first point's section, end conditions and edge, the softest
/// stiffness cap (the largest compliance floor), the sliding term where every point asks for it.
MultiPointElementData multi_point_data(const ActiveContact& contact);

/// The contact element evaluated at d = (u, v, Θ of nodes i, j, then of each point's node).
MultiPointResponse active_contact_response(const ActiveContact& contact, const Eigen::VectorXd& d,
                                           double previous_rotation, bool with_tangent = true);
/// The same into `out`, whose storage is reused where its sizes fit: a one-point element
/// evaluated into the response of one allocates nothing (a Newton iteration evaluates 10⁴ of them).
void active_contact_response(const ActiveContact& contact, const Eigen::VectorXd& d, double previous_rotation,
                             bool with_tangent, MultiPointResponse& out);

}  // namespace tsm::contact
