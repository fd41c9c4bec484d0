#pragma once
// The three-node contact element in the frame its contact asks for (ContactElementData::frame):
// the chord's (Eq. 6–9, contact_element.hpp; with the force along the bent beam's normal where
// ContactElementData::normal asks, deflected_normal_element.hpp) or the cantilever's (FORMULATION
// §2b, cantilever_frame_element.hpp). What assembly evaluates.

#include "tsmframe/contact/contact_element.hpp"

namespace tsm::contact {

/// d = (u_i, v_i, Θ_i, u_j, v_j, Θ_j, u_c, v_c, Θ_c); Θ_c plays no part.
ContactResponse contact_response(const ContactElementData& data, const Vector9& d, double previous_rotation,
                                 bool with_tangent = true);

}  // namespace tsm::contact
