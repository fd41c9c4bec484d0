#include "tsmframe/contact/active_contact.hpp"

#include <algorithm>

#include "tsmframe/contact/contact_response.hpp"
#include "tsmframe/contact/multi_point_cantilever_frame.hpp"
#include "tsmframe/contact/multi_point_deflected_normal.hpp"

namespace tsm::contact {
namespace {

/// The three-node element's response in the k-point form (k = 1), value for value, into `m`
/// (Eigen keeps a vector's or a matrix's storage where the size stays).
void as_multi_point(const ContactResponse& r, bool with_tangent, MultiPointResponse& m) {
  m.chord = r.chord;
  m.alpha.setConstant(1, r.alpha);
  m.normal.setConstant(1, r.normal);
  m.deformations = r.deformations;
  m.forces = r.forces;
  m.nodal_forces = r.nodal_forces;
  m.force_per_Y.setConstant(1, r.force_per_Y);
  m.point_u = r.point_u;
  m.point_stiffness.setConstant(1, 1, r.point_stiffness);
  m.sliding_u = r.sliding_u;
  m.sliding_v = r.sliding_v;
  m.friction.assign(1, r.friction);
  m.friction_u = r.friction_u;
  m.friction_v = r.friction_v;
  if (with_tangent) {
    m.tangent = r.tangent;
    m.symmetric_tangent = r.symmetric_tangent;
  } else {
    m.tangent.resize(0, 0);
    m.symmetric_tangent.resize(0, 0);
  }
}

}  // namespace

MultiPointElementData multi_point_data(const ActiveContact& contact) {
  const ContactElementData& first = contact.data.front();
  MultiPointElementData data;
  data.initial = first.initial;
  data.section = first.section;
  data.k0 = first.k0;
  data.edge = first.edge;
  data.flexibility_i = first.flexibility_i;
  data.flexibility_j = first.flexibility_j;
  data.frame = first.frame;  // every point's (occupancy.hpp)
  for (const ContactElementData& point : contact.data) {
    data.points.push_back({point.contact_start, point.offset, point.normal, point.friction});
    data.min_compliance = std::max(data.min_compliance, point.min_compliance);
    data.sliding_term = data.sliding_term && point.sliding_term;
  }
  return data;
}

MultiPointResponse active_contact_response(const ActiveContact& contact, const Eigen::VectorXd& d,
                                           double previous_rotation, bool with_tangent) {
  MultiPointResponse out;
  active_contact_response(contact, d, previous_rotation, with_tangent, out);
  return out;
}

void active_contact_response(const ActiveContact& contact, const Eigen::VectorXd& d, double previous_rotation,
                             bool with_tangent, MultiPointResponse& out) {
  if (contact.size() == 1) {
    const Vector9 d9 = d;
    const ContactElementData& data = contact.data.front();
    as_multi_point(contact_response(data, d9, previous_rotation, with_tangent), with_tangent, out);
    return;
  }
  const MultiPointElementData data = multi_point_data(contact);
  const bool any_deflected = std::any_of(data.points.begin(), data.points.end(),
                                         [](const ContactPointData& p) { return p.normal == ContactNormal::deflected; });
  if (data.frame == ContactFrame::cantilever) out = multi_point_cantilever_response(data, d, previous_rotation, with_tangent);
  else if (any_deflected) out = multi_point_deflected_response(data, d, previous_rotation, with_tangent);
  else out = multi_point_response(data, d, previous_rotation, with_tangent);
}

}  // namespace tsm::contact
