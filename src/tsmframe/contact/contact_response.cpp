#include "tsmframe/contact/contact_response.hpp"

#include "tsmframe/contact/cantilever_frame_element.hpp"
#include "tsmframe/contact/deflected_normal_element.hpp"

namespace tsm::contact {

ContactResponse contact_response(const ContactElementData& data, const Vector9& d, double previous_rotation,
                                 bool with_tangent) {
  switch (data.frame) {
    case ContactFrame::cantilever: return cantilever_frame_response(data, d, previous_rotation, with_tangent);
    case ContactFrame::chord: break;
  }
  if (data.normal == ContactNormal::deflected) return deflected_normal_response(data, d, previous_rotation, with_tangent);
  return chord_frame_response(data, d, previous_rotation, with_tangent);
}

}  // namespace tsm::contact
