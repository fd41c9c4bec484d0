#pragma once
// Where contacts land, Newton's step is cut short. The linearised step of a free beam above the
// beam it is about to rest on can carry it far through that beam (a 100-m beam pinned at its
// ends sags 10⁵ m under its load in the first iterate of a step); detection then starts hundreds
// of contacts deep inside the other beam, at points the iterates after it bounce between
// elements from (bench/README.md, "The landing"). The step is scaled instead to the fraction that
// leaves every inactive contact's node at most a few of its candidate's element lengths beyond
// the gap of any candidate element it crosses: the contacts start near the surface, and the next
// iterate goes on from there with them in touch.

#include <Eigen/Core>
#include <vector>

#include "tsmframe/contact/contact_geometry.hpp"
#include "tsmframe/contact/contact_state.hpp"

namespace tsm::contact {

/// How deep beyond its gap a node may land in one iterate, in lengths of the element it crosses.
constexpr double landing_depth_in_elements = 2.0;

/// The largest fraction s ∈ (0, 1] of the step from `displacements` to `trial` (all dofs) that
/// leaves the inactive contact's node no deeper than the landing depth beyond the gap of any
/// candidate element whose span it crosses (distances across each chord, linear in s between
/// the two states). The candidates are the broad phase's list at the step's start where the
/// contact has one (a node moving farther than its radius in one iterate meets the nearer
/// elements first), else every candidate.
double landing_fraction(const ContactGeometry& geometry, const ContactCandidates& contact, const ContactState& state,
                        const Eigen::VectorXd& displacements, const Eigen::VectorXd& trial);

/// A contact node put back on the surface it has just landed on: its translation (global).
struct LandingMove {
  int node = -1;  ///< −1: the node stays
  Eigen::Vector2d by = Eigen::Vector2d::Zero();
};

/// The iterate the landing cut short leaves the contacts it started as deep as the cut did (up to
/// the landing depth), and the next iterate would push them out through the beams' geometry, far
/// from its linearisation: with every point's Y ~10⁵ times the beam's force, thousands of them
/// bounced over the lower beam's nodes until the step was cut back (bench/README.md, "Landing on
/// the surface"). A contact that has just started on an element, its node beyond the gap, is
/// moved back along the element's chord normal to the gap (where its Y is zero): the node's
/// translation. Not a vertex's (it rests on two elements).
LandingMove landing_move(const ContactGeometry& geometry, const ContactCandidates& contact, const ContactState& state,
                         const Eigen::VectorXd& displacements, const std::vector<double>& rotations);

}  // namespace tsm::contact
