// The assembled tangent with active contacts (assembly/contact_assembly.cpp through GlobalSystem)
// against central finite differences of the internal forces: a contact inside an element, and a
// vertex (two contact elements at one node).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include <Eigen/Core>

#include "support/contact_models.hpp"
#include "support/dense.hpp"
#include "tsmframe/assembly/dof_map.hpp"
#include "tsmframe/assembly/global_system.hpp"
#include "tsmframe/contact/contact_set.hpp"
#include "tsmframe/contact/friction.hpp"

namespace {

using namespace tsm::test;

// ---- The assembled tangent with active contacts ----

/// ∂F/∂D over the free dofs by central differences (h = 1e-7) at D, with these contacts.
Eigen::MatrixXd finite_difference_tangent(tsm::assembly::GlobalSystem& system, const tsm::assembly::DofMap& dofs,
                                          const Eigen::VectorXd& D, const std::vector<double>& rotations,
                                          const std::vector<tsm::contact::ActiveContact>& active) {
  const int n = dofs.free_count();
  Eigen::MatrixXd fd(n, n);
  for (int q = 0; q < n; ++q) {
    Eigen::VectorXd plus = D, minus = D;
    plus[dofs.dof(q)] += 1e-7;
    minus[dofs.dof(q)] -= 1e-7;
    tsm::assembly::Evaluation ep, em;
    system.evaluate(plus, rotations, false, ep, active);
    system.evaluate(minus, rotations, false, em, active);
    for (int r = 0; r < n; ++r) fd(r, q) = (ep.internal_force[dofs.dof(r)] - em.internal_force[dofs.dof(r)]) / 2e-7;
  }
  return fd;
}

/// A bent, rotated state of every node: (−0.05 x², 0.3 x², 0.6 x) at x as drawn.
Eigen::VectorXd bent_and_turned(const tsm::Model& model) {
  Eigen::VectorXd D = Eigen::VectorXd::Zero(model.dof_count());
  for (int k = 0; k < model.node_count(); ++k) {
    const double x = model.nodes[k].position.x();
    D.segment<3>(3 * k) << -0.05 * x * x, 0.3 * x * x, 0.6 * x;
  }
  return D;
}

/// bent_and_turned with the post's free bottom (node 100) pressed 0.02 into the beam at x = 0.45
/// (near α = 0.7 of its element).
Eigen::VectorXd post_pressed_in(const tsm::Model& model) {
  Eigen::VectorXd D = bent_and_turned(model);
  const double x_c = 0.45;
  D.segment<2>(3 * model.node_index(100)) << -0.05 * x_c * x_c + 0.01, 0.3 * x_c * x_c + 0.02;
  return D;
}

/// The model `m` (post_on_cantilever's) in a bent, rotated state with the pusher pressed 0.02 into
/// the beam near α = 0.7 (post_pressed_in), evaluated once and its contacts updated there.
struct PressedPost {
  tsm::Model model;
  tsm::assembly::DofMap dofs;
  tsm::assembly::GlobalSystem system;
  tsm::contact::ContactSet tracker;
  std::vector<tsm::contact::ContactState> states;
  Eigen::VectorXd D;
  tsm::assembly::Evaluation e;
  explicit PressedPost(const nlohmann::json& m)
      : model(tsm::io::read_model(m)), dofs(model), system(model, dofs), tracker(model),
        states(tracker.initial_states()), D(post_pressed_in(model)) {
    system.evaluate(D, std::vector<double>(model.elements.size(), 0.0), true, e);
    tracker.update(D, e.chord_rotations, e.contacts, states, false, tsm::contact::unloaded_start(model));
  }
};

TEST(ContactAssembly, TangentWithActiveContactsMatchesFiniteDifferences) {
  for (const char* element : {"euler-bernoulli", "timoshenko"}) {
    PressedPost post(post_on_cantilever(element, 0.45));
    auto& [model, dofs, system, tracker, states, D, e] = post;
    ASSERT_TRUE(states[0].active);
    const auto active = tracker.active_contacts(states);
    system.evaluate(D, e.chord_rotations, true, e, active);
    ASSERT_GT(std::abs(e.contacts[0].Y), 1.0);
    // Dense K_ff: block part (mirrored; the contact element's symmetric part is in it, the post
    // node joined to the beam's nodes by a pattern the contact added) plus the sliding term.
    ASSERT_EQ(system.contact_rank_one().size(), 1u);  // the sliding term, kept apart for Woodbury
    const Eigen::MatrixXd K = dense_tangent(dofs, system.tangent(), system.contact_rank_one());
    const Eigen::MatrixXd fd = finite_difference_tangent(system, dofs, D, e.chord_rotations, active);
    EXPECT_LE((K - fd).norm(), 1e-6 * fd.norm()) << element;
    EXPECT_GT((K - K.transpose()).norm(), 1e-8 * K.norm()) << "the sliding term makes it non-symmetric";
  }
}

TEST(ContactAssembly, TangentWithFrictionMatchesFiniteDifferencesInStickAndInSlip) {
  // The pusher pressed in as above, with Coulomb friction and its anchor put behind or ahead of
  // the point: sticking (a quarter of the bound) and slipping (three times it), either way.
  for (const char* element : {"euler-bernoulli", "timoshenko"})
    for (const double share : {0.25, -0.25, 3.0, -3.0}) {
      nlohmann::json json = post_on_cantilever(element, 0.45);
      json["contacts"][0]["friction"] = 0.3;
      PressedPost post(json);
      auto& [model, dofs, system, tracker, states, D, e] = post;
      ASSERT_TRUE(states[0].active);
      states[0].entering = false;
      // Where the point is: evaluated once without an anchor (it anchors there), then the anchor moved.
      system.evaluate(D, e.chord_rotations, true, e, tracker.active_contacts(states));
      tracker.record(e.contacts, states);
      tsm::contact::FrictionState& f = states[0].friction;
      ASSERT_TRUE(f.anchored);
      const double compression = -states[0].side * e.contacts[0].Y;
      ASSERT_GT(compression, 1.0);
      const auto active = tracker.active_contacts(states);
      const tsm::contact::ContactElementData& data = active[0].data.front();
      const double c_T = tsm::contact::tangential_compliance(data.section.EA, data.initial.length, e.contacts[0].alpha,
                                                             data.edge, data.friction.min_compliance).value;
      f.anchor -= share * 0.3 * compression * c_T;
      const auto moved = tracker.active_contacts(states);
      system.evaluate(D, e.chord_rotations, true, e, moved);
      ASSERT_EQ(e.contacts[0].friction.status,
                std::abs(share) < 1 ? tsm::contact::FrictionStatus::stick : tsm::contact::FrictionStatus::slip);
      std::vector<tsm::linalg::RankOne> terms = system.contact_rank_one();
      ASSERT_FALSE(system.friction_rank_one().empty());
      terms.insert(terms.end(), system.friction_rank_one().begin(), system.friction_rank_one().end());
      const Eigen::MatrixXd K = dense_tangent(dofs, system.tangent(), terms);
      const Eigen::MatrixXd fd = finite_difference_tangent(system, dofs, D, e.chord_rotations, moved);
      EXPECT_LE((K - fd).norm(), 1e-6 * fd.norm()) << element << " share " << share;
    }
}

// ---- The pattern's contact pairs ----

TEST(ContactAssembly, APairNoLongerInTouchLeavesThePatternWhenForgottenAndTheTangentStaysTheSame) {
  // The post pressed onto the cantilever joins its node to the element's two in the pattern.
  // Released, the pair stays (a contact that lets go and comes back would rebuild it) until
  // the pattern is told to forget it at the next evaluation with tangent: then the entries
  // and their fill go, and the tangent's values are what they were.
  const tsm::Model model = tsm::io::read_model(post_on_cantilever("timoshenko", 0.45));
  tsm::assembly::DofMap dofs(model);
  tsm::assembly::GlobalSystem system(model, dofs);
  tsm::contact::ContactSet tracker(model);
  std::vector<tsm::contact::ContactState> states = tracker.initial_states();
  const Eigen::VectorXd D = post_pressed_in(model);
  std::vector<double> rotations(model.elements.size(), 0.0);
  tsm::assembly::Evaluation e;
  system.evaluate(D, rotations, true, e);
  const size_t alone = system.tangent().row.size();
  tracker.update(D, e.chord_rotations, e.contacts, states, false, tsm::contact::unloaded_start(model));
  ASSERT_TRUE(states[0].active);
  const auto active = tracker.active_contacts(states);
  system.evaluate(D, e.chord_rotations, true, e, active);
  const size_t in_touch = system.tangent().row.size();
  ASSERT_GT(in_touch, alone);
  tsm::assembly::Evaluation released;
  system.evaluate(D, e.chord_rotations, true, released);
  EXPECT_EQ(system.tangent().row.size(), in_touch);
  const Eigen::MatrixXd kept = dense_tangent(dofs, system.tangent(), {});
  const int version = system.pattern_version();
  system.forget_contact_pairs();
  system.evaluate(D, e.chord_rotations, true, released);
  EXPECT_EQ(system.tangent().row.size(), alone);
  EXPECT_NE(system.pattern_version(), version);
  EXPECT_EQ((dense_tangent(dofs, system.tangent(), {}) - kept).cwiseAbs().maxCoeff(), 0.0);
  // In touch again, the pair comes back; told to forget, a pair still in touch stays.
  system.forget_contact_pairs();
  system.evaluate(D, e.chord_rotations, true, e, active);
  EXPECT_EQ(system.tangent().row.size(), in_touch);
  system.forget_contact_pairs();
  system.evaluate(D, e.chord_rotations, true, e, active);
  EXPECT_EQ(system.tangent().row.size(), in_touch);
}

TEST(ContactAssembly, APairTwoBeamsJoinBothWaysIsKeptWhileInUseTheOtherWayRound) {
  // Two overlapping cantilevers, each node a contact node on the other beam ("between"). First
  // the lower beam's tip P is pushed through the upper beam onto an element ending at the upper
  // beam's node Q; then, from afresh, Q is pushed down through the lower beam onto the element
  // ending at P: the same pair of nodes, the contact node the other one. The pattern told to
  // forget what is not in use keeps the pair (it was kept as (contact node, other node), dropped
  // as unused while in use as (other, contact), and its block written past the pattern).
  const tsm::Model model = tsm::io::read_model(crossing_cantilevers(json::array({{{"between", {{0}, {1}}}}}), 0.0, 4, 5));
  const auto node_at = [&](double x, double y) {
    for (int k = 0; k < model.node_count(); ++k)
      if ((model.nodes[k].position - Eigen::Vector2d(x, y)).norm() < 1e-9) return k;
    ADD_FAILURE() << "no node at " << x << ", " << y;
    return 0;
  };
  const int P = node_at(2.0, 0.0), Q = node_at(1.8, 0.05);
  tsm::assembly::DofMap dofs(model);
  tsm::assembly::GlobalSystem system(model, dofs);
  tsm::contact::ContactSet tracker(model);
  const std::vector<double> rotations(model.elements.size(), 0.0);
  // The node `pushed` moved by dy through the other beam, its contact found and in touch.
  const auto in_touch = [&](int pushed, double dy) {
    Eigen::VectorXd D = Eigen::VectorXd::Zero(model.dof_count());
    D[3 * pushed + 1] = dy;
    std::vector<tsm::contact::ContactState> states = tracker.initial_states();
    tsm::assembly::Evaluation e;
    system.evaluate(D, rotations, true, e);
    tracker.update(D, e.chord_rotations, e.contacts, states, false, tsm::contact::unloaded_start(model));
    const auto active = tracker.active_contacts(states);
    EXPECT_EQ(active.size(), 1u);
    for (const auto& a : active) {
      const tsm::Element& element = model.elements[a.element];
      EXPECT_EQ(a.points.at(0).node, pushed);
      EXPECT_TRUE(element.start == (pushed == P ? Q : P) || element.end == (pushed == P ? Q : P)) << a.element;
    }
    return std::make_pair(D, active);
  };
  const auto [up, p_on_upper] = in_touch(P, 0.06);
  tsm::assembly::Evaluation e;
  system.evaluate(up, rotations, true, e, p_on_upper);
  const auto [down, q_on_lower] = in_touch(Q, -0.06);
  system.forget_contact_pairs();
  ASSERT_NO_THROW(system.evaluate(down, rotations, true, e, q_on_lower));
  // The contact element's block between P and Q is in the tangent.
  const Eigen::MatrixXd K = dense_tangent(dofs, system.tangent(), {});
  double coupling = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const int r = dofs.equation(3 * P + i), c = dofs.equation(3 * Q + j);
      if (r >= 0 && c >= 0) coupling = std::max(coupling, std::abs(K(r, c)));
    }
  EXPECT_GT(coupling, 0.0);
}

// ---- Several points on one element (issue 27) ----

TEST(ContactAssembly, TangentWithSeveralPointsOnOneElementMatchesFiniteDifferences) {
  // Three posts' free bottoms on the cantilever's third element (1/3 … 1/2), pressed into a bent,
  // rotated beam: one contact element with three points, their nodes coupled through the beam —
  // along the chord's normal, along the bent beam's, and mixed (the middle point the chord's).
  const char* normals[3][3] = {{"chord", "chord", "chord"}, {"deflected", "deflected", "deflected"}, {"deflected", "chord", "deflected"}};
  for (const auto& normal : normals)
  for (const char* element : {"euler-bernoulli", "timoshenko"}) {
    SCOPED_TRACE(std::string(element) + ", normals " + normal[0] + " " + normal[1] + " " + normal[2]);
    json m = post_on_cantilever(element, 0.36);
    const double xs[3] = {0.36, 0.40, 0.47};
    m["contacts"] = json::array({{{"node", 100}, {"members", {0}}, {"normal", normal[0]}}});
    for (int p = 1; p < 3; ++p) {
      m["nodes"].push_back({{"id", 100 + p}, {"x", xs[p]}, {"y", 0.0}});
      m["nodes"].push_back({{"id", 11 + 10 * p}, {"x", xs[p]}, {"y", 0.5}});
      m["members"].push_back({{"from", 11 + 10 * p}, {"to", 100 + p}, {"divisions", 2}, {"material", "m"}, {"section", "s"}});
      m["supports"].push_back({{"node", 11 + 10 * p}, {"type", "fixed"}});
      m["contacts"].push_back({{"node", 100 + p}, {"members", {0}}, {"normal", normal[p]}});
    }
    const tsm::Model model = tsm::io::read_model(m);
    tsm::assembly::DofMap dofs(model);
    tsm::assembly::GlobalSystem system(model, dofs);
    tsm::contact::ContactSet tracker(model);
    std::vector<tsm::contact::ContactState> states = tracker.initial_states();
    Eigen::VectorXd D = bent_and_turned(model);
    for (int p = 0; p < 3; ++p) {
      const double x = xs[p];
      D.segment<2>(3 * model.node_index(100 + p)) << -0.05 * x * x + 0.01 * p, 0.3 * x * x + 0.02 - 0.01 * p;
      states[p].active = true;
      states[p].element = 2;
      states[p].side = 1;
    }
    const std::vector<double> rotations(model.elements.size(), 0.0);
    const auto active = tracker.active_contacts(states);
    ASSERT_EQ(active.size(), 1u);
    ASSERT_EQ(active[0].size(), 3);
    tsm::assembly::Evaluation e;
    system.evaluate(D, rotations, true, e, active);
    ASSERT_EQ(e.contacts.size(), 3u);
    for (const auto& c : e.contacts) ASSERT_GT(std::abs(c.Y), 1.0);
    ASSERT_EQ(system.contact_rank_one().size(), 3u);  // one sliding term per point
    const Eigen::MatrixXd K = dense_tangent(dofs, system.tangent(), system.contact_rank_one());
    const Eigen::MatrixXd fd = finite_difference_tangent(system, dofs, D, e.chord_rotations, active);
    EXPECT_LE((K - fd).norm(), 1e-6 * fd.norm()) << element;
    // The points' nodes are coupled through the beam (C⁻¹ is not diagonal).
    const int c0 = dofs.equation(3 * model.node_index(100) + 1), c2 = dofs.equation(3 * model.node_index(102) + 1);
    EXPECT_GT(std::abs(K(c0, c2)), 1e-3 * std::abs(K(c0, c0))) << element;
  }
}

// ---- A vertex: two contact elements at one node ----

TEST(ContactVertex, TheAssembledTangentMatchesFiniteDifferences) {
  for (const char* element : {"euler-bernoulli", "timoshenko"}) {
    VertexSetUp v = vertex_set_up(element);
    ASSERT_GE(v.ending, 0);
    ASSERT_GE(v.starting, 0);
    tsm::assembly::DofMap dofs(v.model);
    tsm::assembly::GlobalSystem system(v.model, dofs);
    tsm::contact::ContactSet tracker(v.model);
    const auto active = tracker.active_contacts(v.states);
    ASSERT_EQ(active.size(), 2u);
    std::vector<double> rotations(v.model.elements.size(), 0.0);
    tsm::assembly::Evaluation e;
    system.evaluate(v.D, rotations, true, e, active);
    ASSERT_EQ(e.contacts.size(), 2u);
    ASSERT_GT(std::abs(e.contacts[0].Y), 1.0);
    ASSERT_GT(std::abs(e.contacts[1].Y), 1.0);
    const Eigen::MatrixXd K = dense_tangent(dofs, system.tangent(), system.contact_rank_one());
    const Eigen::MatrixXd fd = finite_difference_tangent(system, dofs, v.D, e.chord_rotations, active);
    EXPECT_LE((K - fd).norm(), 1e-6 * fd.norm()) << element;
  }
}

}  // namespace
