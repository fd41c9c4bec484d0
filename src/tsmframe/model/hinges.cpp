#include "tsmframe/model/hinges.hpp"

namespace tsm {

std::vector<char> turned_nodes(const Model& model) {
  std::vector<char> turned(model.node_count(), 0);
  for (const Element& e : model.elements) {
    if (!e.release_start) turned[e.start] = 1;
    if (!e.release_end) turned[e.end] = 1;
  }
  return turned;
}

std::vector<char> hinge_nodes(const Model& model) {
  const std::vector<char> turned = turned_nodes(model);
  std::vector<char> hinge(model.node_count(), 0);
  for (const Element& e : model.elements) hinge[e.start] = hinge[e.end] = 1;  // held by an element …
  for (int k = 0; k < model.node_count(); ++k) hinge[k] = hinge[k] && !turned[k];  // … turned by none
  return hinge;
}

}  // namespace tsm
