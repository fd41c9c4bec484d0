#include "tsmframe/contact/chord_frames.hpp"

namespace tsm::contact {

void ChordFrames::form() {
  const Model& model = geometry_.model();
  frames_.resize(model.elements.size());
  for (const int e : geometry_.candidate_elements())
    frames_[e] = element::chord_frame(geometry_.initial(e), element_displacements(model.elements[e], displacements_));
}

}  // namespace tsm::contact
