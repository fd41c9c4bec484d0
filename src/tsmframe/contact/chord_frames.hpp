#pragma once
// The candidate elements' current chord frames, each formed once per pass over the contacts
// when first asked for: detection and the reference sides take α of each node on its candidate
// elements, and α alone (the same arithmetic as ContactGeometry::locate's) rules out all but the
// few elements whose span holds the node. Where few nodes are looked for (a press whose contacts
// are nearly all in touch), few frames are formed.

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
    if (formed_.empty()) start();
    if (!formed_[element]) form(element);
    return frames_[element];
  }

 private:
  void start();
  void form(int element);
  const ContactGeometry& geometry_;
  const Eigen::VectorXd& displacements_;
  std::vector<element::ChordFrame> frames_;
  std::vector<char> formed_;  ///< per element: frames_ holds its frame
};

}  // namespace tsm::contact
