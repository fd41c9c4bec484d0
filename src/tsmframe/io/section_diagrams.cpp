#include "tsmframe/io/section_diagrams.hpp"

namespace tsm::io {

std::vector<std::vector<element::SectionStation>> section_diagrams(const Model& model, const solver::StepRecord& step) {
  const size_t n = model.elements.size();
  const auto at = [&](int node) -> Eigen::Vector2d {
    return model.nodes[node].position + step.displacements.segment<2>(dofs_per_node * node);
  };
  std::vector<std::vector<element::PointForce>> points(n);
  for (size_t k = 0; k < step.contacts.size(); ++k) {
    const solver::ContactPoint& c = step.contacts[k];
    if (c.element < 0 || c.partner >= 0 || c.alpha <= 0.0 || c.alpha >= 1.0) continue;  // none, or on a node
    const Element& element = model.elements[c.element];
    const Eigen::Vector2d e = (at(element.end) - at(element.start)).normalized(), normal(-e.y(), e.x());
    // The push the beam takes: Y along the chord's normal, and its share along the chord.
    points[c.element].push_back({c.alpha, c.Y, c.push.dot(e), (at(model.contacts[k].node) - at(element.start)).dot(normal)});
  }
  std::vector<std::vector<element::SectionStation>> diagrams(n);
  for (size_t e = 0; e < n; ++e) {
    const Element& element = model.elements[e];
    diagrams[e] = element::section_forces((at(element.end) - at(element.start)).norm(),
                                          step.element_forces.segment<3>(3 * e), points[e]);
  }
  return diagrams;
}

}  // namespace tsm::io
