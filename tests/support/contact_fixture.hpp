#pragma once
// A small contact model for the life cycle's rules (tests/unit/contact/): a beam of four
// elements along x from (0, 0) to (1, 0) (member 0, elements 0–3 left to right, beam nodes at
// x = 0, 0.25, 0.5, 0.75, 1) and a post (member 1) hanging from (x, y + 0.5) down to its foot at
// (x, y), node 100, the contact node on member 0. Displacements are set by hand.

#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <vector>

#include "support/models.hpp"
#include "tsmframe/contact/contact_geometry.hpp"
#include "tsmframe/contact/contact_state.hpp"
#include "tsmframe/contact/sides.hpp"

namespace tsm::test {

struct ContactFixture {
  Model model;
  Eigen::VectorXd D;
  std::vector<double> rotations;
  int foot = -1;  ///< the contact node's index

  /// The beam and the post, with `contact` (a contacts entry; node and members are set here).
  explicit ContactFixture(double x, double y, json contact = json::object(), int divisions = 4) {
    BeamSpec b;
    b.divisions = divisions;
    b.A = 1e3;
    json m = beam_model(b);
    m["nodes"].push_back({{"id", 100}, {"x", x}, {"y", y}});
    m["nodes"].push_back({{"id", 11}, {"x", x}, {"y", y + 0.5}});
    m["members"].push_back({{"from", 11}, {"to", 100}, {"divisions", 2}, {"material", "m"}, {"section", "s"}});
    m["supports"] = json::array({{{"node", 1}, {"type", "fixed"}}, {{"node", 11}, {"type", "fixed"}}});
    contact["node"] = 100;
    if (!contact.contains("members")) contact["members"] = json::array({0});
    m["contacts"] = json::array({contact});
    model = io::read_model(m);
    foot = model.node_index(100);
    D = Eigen::VectorXd::Zero(model.dof_count());
    rotations.assign(model.elements.size(), 0.0);
  }

  /// Moves the contact node by (dx, dy) from where it was drawn.
  void move_foot(double dx, double dy) { D.segment<2>(dofs_per_node * foot) << dx, dy; }
  /// Bends the beam into v = a x² (its nodes on the parabola, rotations its slope).
  void bend_beam(double a) {
    for (int k = 0; k < model.node_count(); ++k) {
      if (k == foot || model.nodes[k].id == 11 || model.nodes[k].position.y() != 0.0) continue;
      const double x = model.nodes[k].position.x();
      D.segment<3>(dofs_per_node * k) << 0.0, a * x * x, 2.0 * a * x;
    }
  }
  /// The index of the beam's element whose span [x0, x1] holds x (beam elements come first).
  int beam_element(double x) const { return static_cast<int>(x * 4.0); }
};

/// The contact's state with its reference (sides, place, position) read at the fixture's
/// displacements: inactive, as at a converged state.
inline contact::ContactState reference_state(const contact::ContactGeometry& geometry, const ContactFixture& f) {
  contact::ContactState state;
  state.reference.side.set(std::vector<signed char>(geometry.contact(0).candidates.size(), 0));
  contact::reset_sides(geometry, geometry.contact(0), f.D, f.rotations, 0, state);
  contact::keep_place(geometry, geometry.contact(0), f.D, state.reference);  // no step start at hand: its own place
  return state;
}

/// The same, active on `element` from `side`, at α where its node is.
inline contact::ContactState active_state(const contact::ContactGeometry& geometry, const ContactFixture& f, int element,
                                          int side = 1) {
  contact::ContactState state = reference_state(geometry, f);
  state.active = true;
  state.element = element;
  state.side = side;
  state.alpha = geometry.locate(geometry.contact(0), element, f.D, f.rotations).alpha;
  return state;
}

}  // namespace tsm::test
