#pragma once
// Contact models and checks shared by the contact tests (tests/verification/contact/, and the
// unit tests of the contact set and of the assembled tangent with contacts): a cantilever and a
// rigid pusher, a post on a cantilever, a node pressed onto a beam node (a vertex), and the
// global equilibrium and contact point of a step.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "support/models.hpp"
#include "tsmframe/contact/contact_set.hpp"
#include "tsmframe/contact/contact_state.hpp"

namespace tsm::test {

/// A cantilever along x (node 1 clamped) and a rigid pusher, node 100 at (x, y0), moved by
/// (push_x, push_y) at λ = 1; the pusher's rotation and, unless pushed along x, its x are fixed.
inline json pusher_model(const BeamSpec& b, double x, double y0, double push_x, double push_y, int steps) {
  json m = beam_model(b);
  m["nodes"].push_back({{"id", 100}, {"x", x}, {"y", y0}});
  json fix = json::array({"rz"});
  if (push_x == 0.0) fix.push_back("ux");
  m["supports"] = json::array({{{"node", 1}, {"type", "fixed"}}, {{"node", 100}, {"fix", fix}}});
  json prescribed = {{"node", 100}, {"uy", push_y}};
  if (push_x != 0.0) prescribed["ux"] = push_x;
  m["prescribed"] = json::array({prescribed});
  m["contacts"] = json::array({{{"node", 100}, {"members", "all"}}});
  m["analysis"] = {{"control", {{"type", "load"}, {"steps", steps}}}, {"cutback", true}};
  return m;
}

/// Global equilibrium to the accuracy the step reports: a contact next to a beam node is so stiff
/// that its residual may stop at a round-off floor above 1e-9 (criterion "round-off").
inline void expect_equilibrium(const tsm::Model& model, const solver::StepRecord& step) {
  expect_global_equilibrium(model, step, std::max(1e-9, 10.0 * step.residual_norms.back()));
}

inline const tsm::solver::ContactPoint& contact_of(const solver::StepRecord& step, size_t k = 0) { return step.contacts.at(k); }

/// Arc length of the contact point from the clamp on a uniform mesh of n elements of length L/n.
inline double contact_arc_length(const tsm::solver::ContactPoint& c, double L, int n) {
  return (c.element + c.alpha) * L / n;
}

/// The index of the beam node at (x, 0) (not the pusher, node 100).
inline int beam_node_at(const tsm::Model& model, double x) {
  for (int k = 0; k < model.node_count(); ++k)
    if (std::abs(model.nodes[k].position.x() - x) < 1e-12 && model.nodes[k].position.y() == 0.0 && model.nodes[k].id != 100)
      return k;
  return -1;
}

/// A push on a cantilever: its element kind, and the contact element's frame.
struct PushCase {
  const char* element;
  const char* frame;  // "chord" (Eq. 6–9) or "cantilever" (FORMULATION §2b)
};

/// Two overlapping cantilevers (examples/cantilever-on-cantilever-arc-length.json, 2 m, 20
/// elements each unless said), the upper one's tip pushed down by `load` in 10 steps, with
/// `contacts`.
inline json crossing_cantilevers(const json& contacts, double load, int lower = 20, int upper = 20) {
  return {{"materials", {{"steel", {{"E", 2.05e11}, {"nu", 0.3}}}}},
          {"sections", {{"bar", {{"A", 1.0e-3}, {"I", 1.0e-6}}}}},
          {"nodes", json::array({{{"id", 1}, {"x", 0.0}, {"y", 0.0}}, {{"id", 2}, {"x", 2.0}, {"y", 0.0}},
                                 {{"id", 3}, {"x", 3.0}, {"y", 0.05}}, {{"id", 4}, {"x", 1.0}, {"y", 0.05}}})},
          {"members", json::array({{{"from", 1}, {"to", 2}, {"divisions", lower}, {"material", "steel"}, {"section", "bar"}},
                                   {{"from", 3}, {"to", 4}, {"divisions", upper}, {"material", "steel"}, {"section", "bar"}}})},
          {"supports", json::array({{{"node", 1}, {"type", "fixed"}}, {{"node", 3}, {"type", "fixed"}}})},
          {"loads", json::array({{{"node", 4}, {"fy", -load}}})},
          {"contacts", contacts},
          {"analysis", {{"control", {{"type", "load"}, {"steps", 10}}}}}};
}

/// A cantilever of 6 elements (`element`) and a post clamped at its top whose free bottom, node
/// 100 at (x, 0), is the contact node: all of the contact element's dofs are unknowns.
inline json post_on_cantilever(const char* element, double x) {
  BeamSpec b;
  b.divisions = 6;
  b.A = 1e3;
  b.element = element;
  json m = beam_model(b);
  m["nodes"].push_back({{"id", 100}, {"x", x}, {"y", 0.0}});
  m["nodes"].push_back({{"id", 11}, {"x", x}, {"y", 0.5}});
  m["members"].push_back({{"from", 11}, {"to", 100}, {"divisions", 2}, {"material", "m"}, {"section", "s"}});
  m["supports"] = json::array({{{"node", 1}, {"type", "fixed"}}, {{"node", 11}, {"type", "fixed"}}});
  m["contacts"] = json::array({{{"node", 100}, {"members", "all"}}});
  return m;
}

/// post_on_cantilever with the post's free bottom (node 100) pressed onto the
/// beam node at x = 0.5, and a tracker state with both elements at that node in contact.
struct VertexSetUp {
  tsm::Model model;
  Eigen::VectorXd D;
  std::vector<tsm::contact::ContactState> states;
  int ending = -1, starting = -1, node = -1;  // the elements ending and starting at the node
};

inline VertexSetUp vertex_set_up(const char* element) {
  VertexSetUp v;
  v.model = tsm::io::read_model(post_on_cantilever(element, 0.5));
  for (int k = 0; k < v.model.node_count(); ++k)
    if (v.model.nodes[k].id != 100 && v.model.nodes[k].position == Eigen::Vector2d(0.5, 0.0)) v.node = k;
  for (size_t k = 0; k < v.model.elements.size(); ++k) {
    if (v.model.elements[k].member != 0) continue;
    if (v.model.elements[k].end == v.node) v.ending = static_cast<int>(k);
    if (v.model.elements[k].start == v.node) v.starting = static_cast<int>(k);
  }
  // A bent state (the beam kinks at its nodes: chords of a parabola), the pusher 0.02 into it.
  v.D = Eigen::VectorXd::Zero(v.model.dof_count());
  for (int k = 0; k < v.model.node_count(); ++k) {
    const double x = v.model.nodes[k].position.x();
    v.D.segment<3>(3 * k) << -0.05 * x * x, 0.3 * x * x, 0.6 * x;
  }
  v.D.segment<2>(3 * v.model.node_index(100)) << -0.05 * 0.25, 0.3 * 0.25 + 0.02;
  tsm::contact::ContactSet tracker(v.model);
  v.states = tracker.initial_states();
  tsm::contact::ContactState& s = v.states[0];
  s.active = true;
  s.element = v.ending;
  s.vertex = tsm::contact::Vertex{v.starting, -1, 0.0};
  s.side = -1;  // it came from below (y < 0 at the start would be +1: it pushes up), on both elements
  s.alpha = 1.0;
  return v;
}

}  // namespace tsm::test
