#pragma once
// Every candidate element's current chord frame, formed once per pass over the contacts when
// first asked for: detection and the reference sides take α of each node on every candidate,
// and α alone (the same arithmetic as ContactGeometry::locate's) rules out all but the few
// elements whose span holds the node.

#include <Eigen/Core>
#include <vector>

#include "tsmframe/contact/contact_geometry.hpp"
#include "tsmframe/element/chord.hpp"

namespace tsm::contact {

class ChordFrames {
 public:
  ChordFrames(const ContactGeometry& geometry, const Eigen::VectorXd& displacements)
      : geometry_(geometry), displacements_(displacements) {}
  const element::ChordFrame& operator()(int element) {
    if (frames_.empty()) form();
    return frames_[element];
  }

 private:
  void form();
  const ContactGeometry& geometry_;
  const Eigen::VectorXd& displacements_;
  std::vector<element::ChordFrame> frames_;
};

}  // namespace tsm::contact
