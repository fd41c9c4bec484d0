#include "tsmframe/io/element_curves.hpp"

#include <cmath>
#include <numbers>

namespace tsm::io {

element::EndConnections end_connections(const Model& model, const Element& e) {
  return {e.release_start ? INFINITY : model.flexibility_start(e), e.release_end ? INFINITY : model.flexibility_end(e)};
}

double chord_rotation(const Model& model, const Element& e, const Eigen::VectorXd& D, const Eigen::Vector3d& forces) {
  const Eigen::Vector2d Xi = model.nodes[e.start].position, Xj = model.nodes[e.end].position;
  const Eigen::Vector2d xi = Xi + D.segment<2>(dofs_per_node * e.start), xj = Xj + D.segment<2>(dofs_per_node * e.end);
  const double phi0 = std::atan2(Xj.y() - Xi.y(), Xj.x() - Xi.x()), phi = std::atan2(xj.y() - xi.y(), xj.x() - xi.x());
  const double rotation_i = D[dofs_per_node * e.start + rz], rotation_j = D[dofs_per_node * e.end + rz];
  const element::EndConnections ends = end_connections(model, e);
  // What β is near: the mean of the element's own end rotations' carriers, Θ − f·M at each end
  // not hinged (|θ| ≤ π/2 at convergence, so the nearest whole turn is the solver's β).
  double guess = 0.0;
  if (ends.flexibility_i == 0.0 && ends.flexibility_j == 0.0) {
    guess = 0.5 * (rotation_i + rotation_j);
  } else {
    int counted = 0;
    if (!std::isinf(ends.flexibility_i)) guess += rotation_i - ends.flexibility_i * forces[1], ++counted;
    if (!std::isinf(ends.flexibility_j)) guess += rotation_j - ends.flexibility_j * forces[2], ++counted;
    if (counted > 0) guess /= counted;
  }
  const double raw = phi - phi0, turn = 2.0 * std::numbers::pi;
  return raw + turn * std::round((guess - raw) / turn);
}

void element_curve(const Model& model, const Element& e, const Eigen::VectorXd& D, const Eigen::Vector3d& forces,
                   std::span<Eigen::Vector2d> points) {
  const element::InitialChord initial = element::initial_chord(model.nodes[e.start].position, model.nodes[e.end].position);
  element::deflected_curve(initial, element_displacements(D, e.start, e.end), chord_rotation(model, e, D, forces), e.section,
                           end_connections(model, e), points);
}

}  // namespace tsm::io
