#pragma once
// The deflected shape of a two-node element in its chord frame: the transverse deflection w(s),
// s = x/l0 ∈ [0, 1] along the chord, of the beam of Eq. 3 (Euler–Bernoulli) or Eq. 4
// (Timoshenko) whose ends turn by θ_i, θ_j against its chord, with no load between its ends.
// The one formula for all that need it: the contact law's free shape (contact_force_law: its
// h = −N are the fixed-end moments of a unit point load, by Maxwell–Betti), the ParaView files,
// results.json's curves and the Python module's plots.
//
// An element's ends may be joined to their nodes by a hinge (Element::release_*) or a
// rotational spring (end_springs) instead of rigidly: the element's own end rotations then
// differ from its nodes' and are condensed out as in connected_stiffness — a hinged end's moment
// is 0 (an element hinged at both ends is straight), a spring's end turns by M/k less than its
// node. Pure and local, like force_law: nothing here knows about nodes or the model.

#include <span>

#include "tsmframe/element/chord.hpp"
#include "tsmframe/element/force_law.hpp"

namespace tsm::element {

/// The shape functions of the end rotations, w(s) = N_i(s) θ_i + N_j(s) θ_j (`i`, `j`), or
/// their derivatives d/ds.
struct RotationShape {
  double i = 0.0;
  double j = 0.0;
};
/// N_i(s), N_j(s) of the element of Eq. 4 (Ψ = 0: Eq. 3's Hermite cubics); s ∈ [0, 1].
RotationShape rotation_shape(const SectionStiffness& section, double l0, double s);
/// dN_i/ds, dN_j/ds.
RotationShape rotation_shape_slope(const SectionStiffness& section, double l0, double s);

/// How each end of an element is joined to its node: the rotational flexibility 1/k of the
/// spring between them (0: rigid; INFINITY: a hinge), as connected_stiffness takes it.
struct EndConnections {
  double flexibility_i = 0.0;
  double flexibility_j = 0.0;
};

/// The element's own end rotations against its chord (θ_i, θ_j) when its nodes turn by
/// `node_rotations` against it (Θ − β), its connections condensed: rigid ends keep the node's, a
/// hinged end turns as its zero moment makes it, a sprung end by the node's less f·M.
Eigen::Vector2d element_end_rotations(const SectionStiffness& section, double l0, const Eigen::Vector2d& node_rotations,
                                      const EndConnections& ends);

/// The shape of one element at one state: w(s) and its slope.
struct DeflectedShape {
  SectionStiffness section;
  double l0 = 0.0;
  Eigen::Vector2d end_rotations = Eigen::Vector2d::Zero();  ///< the element's own θ_i, θ_j

  /// w(s): the transverse deflection off the chord at s = x/l0, along n (the chord turned +90°).
  double deflection(double s) const;
  /// dw/dx at s. The end slopes are the end rotations for Euler–Bernoulli; a Timoshenko beam's
  /// slope is its sections' rotation plus the shear strain, θ + γ.
  double slope(double s) const;
};
DeflectedShape deflected_shape(const SectionStiffness& section, double l0, const Eigen::Vector2d& node_rotations,
                               const EndConnections& ends);

/// The deflected curve in global coordinates: points[k] = x_i + s_k (x_j − x_i) + w(s_k) n,
/// s_k = k / (points.size() − 1), for the element drawn as `initial`, at end displacements
/// d = (u_i, v_i, Θ_i, u_j, v_j, Θ_j) with chord rotation β (a true total, as the solver tracks
/// it: the node rotations against the chord are Θ − β). points.size() ≥ 2.
void deflected_curve(const InitialChord& initial, const Vector6& d, double chord_rotation,
                     const SectionStiffness& section, const EndConnections& ends, std::span<Vector2> points);

}  // namespace tsm::element
