#include "tsmframe/contact/chord_frames.hpp"

namespace tsm::contact {

void ChordFrames::start() {
  const size_t n = geometry_.model().elements.size();
  frames_.resize(n);
  formed_.assign(n, 0);
}

void ChordFrames::form(int element) {
  frames_[element] = element::chord_frame(geometry_.initial(element),
                                          element_displacements(geometry_.model().elements[element], displacements_));
  formed_[element] = 1;
}

}  // namespace tsm::contact
