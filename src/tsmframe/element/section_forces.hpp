#pragma once
// The section forces along an element — the N, V, M diagrams — in its chord frame (FORMULATION
// §0–2): N the axial force (tension positive); M the bending moment, positive where the element
// bends towards its left side (+n: sagging for an element drawn left to right, its right side in
// tension); V = dM/dx. Between its ends and its contact points no load acts on an element (a
// member's pressure, self-weight and foundation are lumped at its nodes), so M is linear there
// and V constant; a contact point's transverse force makes V jump by it and M kink. Pure and
// local, like force_law: the element's forces and points in, the stations out.

#include <Eigen/Core>
#include <span>
#include <vector>

namespace tsm::element {

/// A force on the element between its ends, at α along the chord (0 < α < 1): Y along n (the
/// chord turned +90°), as the contact element carries it (Eq. 6–9), and T along the chord e — the
/// share of a push along the bent beam's normal, −Y w' (docs/contact-normal.md, N4) — acting at
/// ρ across the chord (the contact node's height above it), so that it adds a couple −ρT there.
struct PointForce {
  double alpha = 0.0;
  double Y = 0.0;
  double T = 0.0;
  double rho = 0.0;
};

/// The section forces at x from the element's start node along its chord.
struct SectionStation {
  double x = 0.0;
  double N = 0.0, V = 0.0, M = 0.0;
};

/// The stations along an element of current chord length `l` carrying `forces` = (N, M_i, M_j)
/// (the end moments acting on the element, counter-clockwise positive) and the point forces
/// `points`: x = 0, each point twice (the values just before and just after it), x = l, in order
/// along the element. Exact for the element's statics: M(0) = −M_i, M(l) = M_j, and the points'
/// forces shared by its ends by the lever rule (N8), so that N(0) = N + Σ (1 − α) T.
std::vector<SectionStation> section_forces(double l, const Eigen::Vector3d& forces, std::span<const PointForce> points);

/// The section forces at x along an element from its stations (section_forces): N and V of the
/// stretch holding x, M interpolated along it; at a point's x, the values just past it.
SectionStation section_at(std::span<const SectionStation> stations, double x);

}  // namespace tsm::element
