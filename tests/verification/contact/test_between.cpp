// Beam on beam from both sides (issue 27, part 3): a "between" entry makes every node of each
// beam a contact node on the other, so the answer no longer depends on which beam is the
// "slave" and neither beam's nodes pass through the other.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

#include "support/contact_models.hpp"

namespace {

using namespace tsm::test;

/// The compression at the contact of node `id` at the last step (0 if it has none or is inactive).
double force_at(const tsm::Model& model, const tsm::solver::RunResult& r, int id) {
  for (size_t k = 0; k < model.contacts.size(); ++k)
    if (model.nodes[model.contacts[k].node].id == id) return contact_of(r.steps.back(), k).force;
  return 0.0;
}

TEST(ContactBetween, EveryNodeOfEachBeamIsAContactNodeOnTheOther) {
  tsm::Model model;
  model = tsm::io::read_model(crossing_cantilevers(json::array({{{"between", {{0}, {1}}}}}), 1.0));
  ASSERT_EQ(model.contacts.size(), 42u);  // 21 nodes on each beam
  for (const tsm::ContactSpec& c : model.contacts) {
    ASSERT_EQ(c.members.size(), 1u);
    for (const tsm::Element& e : model.elements)
      if (e.start == c.node || e.end == c.node) EXPECT_NE(e.member, c.members[0]) << "a node touches its own beam";
  }
}

TEST(ContactBetween, CrossingCantileversGiveTheSameTipForceWithEitherBeamFirst) {
  // The upper tip lands on the lower beam and presses it down: with node-to-beam entries for
  // both tips (the example's), or "between" in either order, the tip force is the same.
  const double load = 2e4;
  tsm::Model tips_model, ab_model, ba_model;
  const auto tips = run(crossing_cantilevers(json::array({{{"node", 4}, {"members", {0}}}, {{"node", 2}, {"members", {1}}}}), load), tips_model);
  const auto ab = run(crossing_cantilevers(json::array({{{"between", {{0}, {1}}}}}), load), ab_model);
  const auto ba = run(crossing_cantilevers(json::array({{{"between", {{1}, {0}}}}}), load), ba_model);
  for (const auto* r : {&tips, &ab, &ba}) ASSERT_EQ(r->status, tsm::solver::Status::converged) << r->message;
  const double force = force_at(tips_model, tips, 4);
  ASSERT_GT(force, 0.5 * load);  // most of the load goes into the lower beam
  // Order makes no difference; against the two-entry model, Newton's tolerance (its iterates
  // differ: the other nodes are checked, and stay apart).
  EXPECT_NEAR(force_at(ab_model, ab, 4), force_at(ba_model, ba, 4), 1e-12 * force);
  EXPECT_NEAR(force_at(ab_model, ab, 4), force, 1e-6 * force);
  // No other node touches: the lower tip stays below the upper beam, the rest apart.
  for (const auto& [model, r] : {std::pair{&ab_model, &ab}, std::pair{&ba_model, &ba}}) {
    int touching = 0;
    for (const auto& c : r->steps.back().contacts) touching += c.element >= 0;
    EXPECT_EQ(touching, 1);
  }
}

/// A simply supported stiff beam A (10 m, 4 elements) and a flexible pinned beam B above it
/// (1.1 … 8.9 m, 39 elements, 5 cm up), B pushed down at x = 3.7 m — over the interior of A's
/// second element — with `contacts`.
json beam_over_coarse_beam(const json& contacts) {
  return {{"materials", {{"steel", {{"E", 2e11}, {"nu", 0.3}}}}},
          {"sections", {{"stiff", {{"A", 4e-3}, {"I", 2e-5}}}, {"soft", {{"A", 1e-3}, {"I", 1e-7}}}}},
          {"nodes", json::array({{{"id", 1}, {"x", 0.0}, {"y", 0.0}}, {{"id", 2}, {"x", 10.0}, {"y", 0.0}},
                                 {{"id", 3}, {"x", 1.1}, {"y", 0.05}}, {{"id", 4}, {"x", 8.9}, {"y", 0.05}},
                                 {{"id", 5}, {"x", 3.7}, {"y", 0.05}}})},
          {"members", json::array({{{"from", 1}, {"to", 2}, {"divisions", 4}, {"material", "steel"}, {"section", "stiff"}},
                                   {{"from", 3}, {"to", 5}, {"divisions", 13}, {"material", "steel"}, {"section", "soft"}},
                                   {{"from", 5}, {"to", 4}, {"divisions", 26}, {"material", "steel"}, {"section", "soft"}}})},
          {"supports", json::array({{{"node", 1}, {"type", "pinned"}}, {{"node", 2}, {"type", "roller-x"}},
                                    {{"node", 3}, {"type", "pinned"}}, {{"node", 4}, {"type", "pinned"}}})},
          {"loads", json::array({{{"node", 5}, {"fy", -1000.0}}})},
          {"contacts", contacts},
          {"analysis", {{"control", {{"type", "load"}, {"steps", 10}}}}}};
}

TEST(ContactBetween, AFlexibleBeamPushedBetweenACoarseBeamsNodesRestsOnItInsteadOfPassingThrough) {
  // With the coarse beam's nodes as contact nodes on the flexible one (one way), the flexible
  // beam sags down between them, through the coarse beam's element. With "between" its nodes
  // touch the coarse beam too, and none ends below it.
  tsm::Model one_way_model, both_model;
  const auto one_way = run(beam_over_coarse_beam(json::array({{{"nodes", {{"members", {0}}}}, {"members", {1, 2}}}})), one_way_model);
  const auto both = run(beam_over_coarse_beam(json::array({{{"between", {{0}, {1, 2}}}}})), both_model);
  ASSERT_EQ(one_way.status, tsm::solver::Status::converged) << one_way.message;
  ASSERT_EQ(both.status, tsm::solver::Status::converged) << both.message;
  // How far the flexible beam's lowest node lies below the coarse beam's chords.
  const auto deepest = [](const tsm::Model& model, const tsm::solver::RunResult& r) {
    const auto at = [&](int node) { return node_position(model, r.steps.back(), model.nodes[node].id); };
    double deepest = -INFINITY;
    for (const tsm::Element& e : model.elements) {
      if (e.member == 0) continue;
      const Eigen::Vector2d p = at(e.end);
      for (const tsm::Element& f : model.elements) {
        if (f.member != 0) continue;
        const Eigen::Vector2d a = at(f.start), b = at(f.end);
        if (p.x() < a.x() || p.x() > b.x()) continue;
        deepest = std::max(deepest, a.y() + (p.x() - a.x()) / (b.x() - a.x()) * (b.y() - a.y()) - p.y());
      }
    }
    return deepest;
  };
  // The coarse beam's bent elements sag below their chords by ~10⁻⁴ m, where contact is made.
  EXPECT_GT(deepest(one_way_model, one_way), 3e-3) << "one way, the flexible beam passes through";
  EXPECT_LT(deepest(both_model, both), 3e-4) << "between, it rests on the coarse beam";
  int touching = 0;
  for (size_t k = 0; k < both_model.contacts.size(); ++k) touching += contact_of(both.steps.back(), k).element >= 0;
  EXPECT_GE(touching, 1);
  expect_equilibrium(both_model, both.steps.back());
}

TEST(ContactBetween, NodesRestingOnEachOtherPressOnce) {
  // Two equal beams (10 m, 10 elements), the upper one drawn at the gap above the lower and
  // loaded along its length: each upper node rests on a lower node and each lower node on an
  // upper one. One contact carries each pair (the first to touch); the loads go through.
  json m = {{"materials", {{"steel", {{"E", 2e11}, {"nu", 0.3}}}}},
            {"sections", {{"s", {{"A", 4e-3}, {"I", 2e-5}}}}},
            {"nodes", json::array({{{"id", 1}, {"x", 0.0}, {"y", 0.0}}, {{"id", 2}, {"x", 10.0}, {"y", 0.0}},
                                   {{"id", 3}, {"x", 0.0}, {"y", 0.1}}, {{"id", 4}, {"x", 10.0}, {"y", 0.1}}})},
            {"members", json::array({{{"from", 1}, {"to", 2}, {"divisions", 10}, {"material", "steel"}, {"section", "s"}},
                                     {{"from", 3}, {"to", 4}, {"divisions", 10}, {"material", "steel"}, {"section", "s"},
                                      {"load", {{"fy", -1000.0}}}}})},
            {"supports", json::array({{{"node", 1}, {"type", "pinned"}}, {{"node", 2}, {"type", "roller-x"}},
                                      {{"node", 3}, {"fix", {"ux"}}}})},
            {"contacts", json::array({{{"between", {{0}, {1}}}, {"gap", 0.1}}})},
            {"analysis", {{"control", {{"type", "load"}, {"steps", 2}}}}}};
  tsm::Model model;
  const tsm::solver::RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  const auto& contacts = r.steps.back().contacts;
  double total = 0.0;
  for (size_t j = 0; j < contacts.size(); ++j) {
    if (contacts[j].element < 0) continue;
    total += contacts[j].force;
    const int n = model.contacts[j].node;
    const tsm::Element& g = model.elements[contacts[j].element];
    for (size_t k = 0; k < contacts.size(); ++k) {  // the node it rests on does not rest on it as well
      if (k == j || contacts[k].element < 0) continue;
      const int e = model.contacts[k].node;
      const tsm::Element& f = model.elements[contacts[k].element];
      const bool pair = (e == g.start || e == g.end) && (n == f.start || n == f.end);
      EXPECT_FALSE(pair) << "nodes " << model.nodes[n].id << " and " << model.nodes[e].id << " press each other twice";
    }
  }
  // The upper beam's 10 kN, all through the contacts (the normals lean by the slopes, ~10⁻³).
  EXPECT_NEAR(total, 1e4, 1e-4 * 1e4);
}

/// Two equal shallow arcs (span 2 m, rise 0.2 m) drawn crown to crown, the lower one's ends
/// pinned, the upper one's pushed down 5 cm; `lower` and `upper` elements (odd: each crown lies
/// within an element), one "between" entry.
json arcs_crown_to_crown(int lower, int upper) {
  const double R = 2.6, sweep = 2.0 * std::asin(1.0 / R);
  const auto arc = [&](int from, int to, double centre_y, int divisions) {
    return json{{"from", from}, {"to", to}, {"arc", {{"center", {0.0, centre_y}}, {"sweep", sweep}}},
                {"divisions", divisions}, {"material", "steel"}, {"section", "s"}};
  };
  return {{"materials", {{"steel", {{"E", 2e11}, {"nu", 0.3}}}}},
          {"sections", {{"s", {{"A", 1e-3}, {"I", 1e-7}}}}},
          {"nodes", json::array({{{"id", 1}, {"x", 1.0}, {"y", 0.0}}, {{"id", 2}, {"x", -1.0}, {"y", 0.0}},
                                 {{"id", 3}, {"x", -1.0}, {"y", 0.4}}, {{"id", 4}, {"x", 1.0}, {"y", 0.4}}})},
          {"members", json::array({arc(1, 2, 0.2 - R, lower), arc(3, 4, 0.2 + R, upper)})},
          {"supports", json::array({{{"node", 1}, {"type", "pinned"}}, {{"node", 2}, {"type", "pinned"}},
                                    {{"node", 3}, {"fix", {"ux"}}}, {{"node", 4}, {"fix", {"ux"}}}})},
          {"prescribed", json::array({{{"node", 3}, {"uy", -0.05}}, {{"node", 4}, {"uy", -0.05}}})},
          {"contacts", json::array({{{"between", {{0}, {1}}}}})},
          {"analysis", {{"control", {{"type", "load"}, {"steps", 10}}}}}};
}

TEST(ContactBetween, TwoArcsPressedCrownToCrownTouchAtInteriorPointsOfBoth) {
  // The second case. Swapping the meshes mirrors the problem about the line between the
  // arcs: the same forces to rounding. The push the upper supports need converges with the mesh
  // (against 81 / 83 elements), and on the finer meshes nodes of both arcs carry contact — each
  // pressing on the other arc between its nodes, none through it.
  struct Run {
    tsm::Model model;
    tsm::solver::RunResult r;
    double push() const {
      const Eigen::VectorXd& reactions = r.steps.back().reactions;
      return -(reactions[3 * model.node_index(3) + 1] + reactions[3 * model.node_index(4) + 1]);
    }
  };
  const auto solve = [](int lower, int upper) {
    Run out;
    out.r = run(arcs_crown_to_crown(lower, upper), out.model);
    return out;
  };
  const Run a = solve(9, 11), b = solve(11, 9), fine = solve(81, 83);
  for (const Run* x : {&a, &b, &fine}) ASSERT_EQ(x->r.status, tsm::solver::Status::converged) << x->r.message;
  EXPECT_NEAR(a.push(), b.push(), 1e-9 * a.push());  // mirrored
  EXPECT_GT(a.push(), 5e4);
  for (int divisions : {21, 41}) {
    const Run x = solve(divisions, divisions + 2);
    ASSERT_EQ(x.r.status, tsm::solver::Status::converged) << x.r.message;
    std::printf("[figure] %d / %d elements: push %.2f N, the 81 / 83 mesh's %.2f N\n", divisions, divisions + 2, x.push(), fine.push());
    EXPECT_NEAR(x.push(), fine.push(), (divisions == 21 ? 1e-2 : 1e-3) * fine.push());
  }
  int lower_nodes = 0, upper_nodes = 0;
  const auto& contacts = fine.r.steps.back().contacts;
  for (size_t k = 0; k < contacts.size(); ++k) {
    if (contacts[k].element < 0) continue;
    const bool on_upper = fine.model.elements[contacts[k].element].member == 1;
    (on_upper ? lower_nodes : upper_nodes) += 1;
    EXPECT_GT(contacts[k].alpha, 0.0);  // between the touched arc's nodes
    EXPECT_LT(contacts[k].alpha, 1.0);
  }
  EXPECT_GT(lower_nodes, 0);
  EXPECT_GT(upper_nodes, 0);
  // Every contact in compression.
  for (const auto& c : contacts)
    if (c.element >= 0) EXPECT_GE(c.force, 0.0);
}

}  // namespace
