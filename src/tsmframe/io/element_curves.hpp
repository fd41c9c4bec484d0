#pragma once
// A model's elements drawn as their deflected curves at a converged state (element/deflected_shape,
// with each element's hinges and end springs): what the ParaView files, results.json's "curves"
// and the Python module's plots show.

#include <Eigen/Core>
#include <span>

#include "tsmframe/element/deflected_shape.hpp"
#include "tsmframe/model/model.hpp"

namespace tsm::io {

/// Segments of each element's curve (points: one more).
inline constexpr int curve_segments = 8;

/// How element e's ends join its nodes: a release is a hinge (INFINITY), an end spring its
/// flexibility, else 0.
element::EndConnections end_connections(const Model& model, const Element& e);

/// The chord rotation β of element e at displacements D with element forces (N, M_i, M_j): the
/// current chord angle less the drawn one, plus the whole turns that bring the element's own end
/// rotations within half a turn (the solver keeps them within a quarter). From the ends that are
/// not hinged, each turned by its node's rotation less its spring's f·M; an element hinged at
/// both ends has no own end rotation (it is straight), and its β is taken within [−π, π].
double chord_rotation(const Model& model, const Element& e, const Eigen::VectorXd& D, const Eigen::Vector3d& forces);

/// Element e's deflected curve at displacements D and element forces (N, M_i, M_j) (a step's
/// displacements and element_forces): points.size() ≥ 2 positions at s = k / (points.size() − 1)
/// along the chord, in global coordinates.
void element_curve(const Model& model, const Element& e, const Eigen::VectorXd& D, const Eigen::Vector3d& forces,
                   std::span<Eigen::Vector2d> points);

}  // namespace tsm::io
