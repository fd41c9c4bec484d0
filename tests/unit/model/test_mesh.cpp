// Meshing members into nodes and elements (model/mesh.hpp): equal divisions along a chord or an
// arc with the generated nodes numbered after the largest id, distributed loads lumped half to
// each element end, hinge rotations fixed and the default monitored nodes — against hand values.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "tsmframe/model/mesh.hpp"

namespace {

using tsm::Arc;
using tsm::MemberInput;
using tsm::MemberMesh;
using tsm::MeshError;
using tsm::Model;
using std::numbers::pi;

Model nodes_only(std::vector<tsm::Node> nodes, double size) {
  Model model;
  model.nodes = std::move(nodes);
  model.size = size;
  return model;
}

MemberInput member(int from, int to, long divisions) {
  MemberInput m;
  m.from = from;
  m.to = to;
  m.divisions = divisions;
  m.section = {1.0, 1.0, 0.0};
  return m;
}

TEST(MemberMesh, DividesAMemberIntoEqualElementsNumberingNewNodesAfterTheLargestId) {
  // Nodes 1 (0, 0), 2 (3, 0) and 5 (0, 1): a member 1 → 2 in 3 elements adds nodes 6 and 7 at
  // x = 1 and 2; a second member 2 → 5 in 2 elements adds node 8 at its middle, (1.5, 0.5).
  Model model = nodes_only({{1, {0, 0}}, {2, {3, 0}}, {5, {0, 1}}}, std::sqrt(10.0));
  MemberMesh mesh(model);
  MemberInput first = member(0, 1, 3);
  first.release_start = first.release_end = true;
  mesh.add(first);
  mesh.add(member(1, 2, 2));
  mesh.finish();
  ASSERT_EQ(model.node_count(), 6);
  EXPECT_EQ(model.nodes[3].id, 6);
  EXPECT_EQ(model.nodes[4].id, 7);
  EXPECT_EQ(model.nodes[5].id, 8);
  EXPECT_NEAR((model.nodes[3].position - Eigen::Vector2d(1, 0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((model.nodes[4].position - Eigen::Vector2d(2, 0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((model.nodes[5].position - Eigen::Vector2d(1.5, 0.5)).norm(), 0.0, 1e-15);
  EXPECT_EQ(model.member_count, 2);
  ASSERT_EQ(model.elements.size(), 5u);
  const int starts[] = {0, 3, 4, 1, 5}, ends[] = {3, 4, 1, 5, 2}, members[] = {0, 0, 0, 1, 1};
  for (int k = 0; k < 5; ++k) {
    EXPECT_EQ(model.elements[k].id, k + 1);
    EXPECT_EQ(model.elements[k].start, starts[k]) << k;
    EXPECT_EQ(model.elements[k].end, ends[k]) << k;
    EXPECT_EQ(model.elements[k].member, members[k]) << k;
  }
  // The hinges sit at the member's ends only: its first element's start, its last element's end.
  EXPECT_TRUE(model.elements[0].release_start);
  EXPECT_FALSE(model.elements[0].release_end);
  EXPECT_FALSE(model.elements[1].release_start || model.elements[1].release_end);
  EXPECT_TRUE(model.elements[2].release_end);
  EXPECT_TRUE(model.elements[0].member_start && model.elements[2].member_end && !model.elements[1].member_start);
  // The dof arrays: 3 per node, all free, unloaded, nothing prescribed.
  EXPECT_EQ(model.constrained.size(), 18u);
  EXPECT_EQ(model.reference_load.size(), 18);
  EXPECT_EQ(model.reference_load.norm(), 0.0);
}

TEST(MemberMesh, DividesAnArcIntoEqualAnglesAboutItsCentre) {
  // A quarter circle of radius 2 about (1, 1) from (3, 1) to (1, 3) in 3 elements: interior
  // nodes at 30° and 60°.
  Model model = nodes_only({{1, {3, 1}}, {2, {1, 3}}}, std::sqrt(8.0));
  MemberMesh mesh(model);
  MemberInput quarter = member(0, 1, 3);
  quarter.arc = Arc{{1, 1}, pi / 2};
  mesh.add(quarter);
  ASSERT_EQ(model.node_count(), 4);
  EXPECT_NEAR((model.nodes[2].position - Eigen::Vector2d(1 + std::sqrt(3.0), 2)).norm(), 0.0, 1e-14);
  EXPECT_NEAR((model.nodes[3].position - Eigen::Vector2d(2, 1 + std::sqrt(3.0))).norm(), 0.0, 1e-14);
}

TEST(MemberMesh, ClosesAFullCircleOnItsFirstNode) {
  // A ring of radius 1 about the origin from (1, 0) back to it, clockwise (−2π), in 4 elements.
  Model model = nodes_only({{1, {1, 0}}}, 1.0);
  MemberMesh mesh(model);
  MemberInput ring = member(0, 0, 4);
  ring.arc = Arc{{0, 0}, -2 * pi};
  mesh.add(ring);
  ASSERT_EQ(model.node_count(), 4);
  EXPECT_NEAR((model.nodes[1].position - Eigen::Vector2d(0, -1)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((model.nodes[2].position - Eigen::Vector2d(-1, 0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((model.nodes[3].position - Eigen::Vector2d(0, 1)).norm(), 0.0, 1e-15);
  ASSERT_EQ(model.elements.size(), 4u);
  EXPECT_EQ(model.elements[3].start, 3);
  EXPECT_EQ(model.elements[3].end, 0);
}

/// The value a MeshError names and its reason, from meshing `m` on nodes (0, 0), (4, 0).
std::pair<MeshError::Value, std::string> mesh_error(const MemberInput& m) {
  Model model = nodes_only({{1, {0, 0}}, {2, {4, 0}}}, 4.0);
  MemberMesh mesh(model);
  try {
    mesh.add(m);
  } catch (const MeshError& e) {
    return {e.value(), e.what()};
  }
  return {MeshError::Value::member, "no error"};
}

TEST(MemberMesh, RefusesGeometryThatMakesNoMemberNamingTheValueAtFault) {
  EXPECT_EQ(mesh_error(member(0, 0, 2)), std::make_pair(MeshError::Value::member, std::string("zero-length member (from and to are the same point)")));
  MemberInput arc = member(0, 1, 2);
  arc.arc = Arc{{0, 0}, pi};  // the centre is the start node
  EXPECT_EQ(mesh_error(arc), std::make_pair(MeshError::Value::arc_centre, std::string("the centre coincides with the start node")));
  arc.arc = Arc{{1, 0}, pi};  // radius 1 at the start, 3 at the end
  EXPECT_EQ(mesh_error(arc).first, MeshError::Value::arc_centre);
  EXPECT_EQ(mesh_error(arc).second, "the start and end nodes are not on one circle about the centre");
  arc.arc = Arc{{2, 0}, pi / 2};  // a half circle about (2, 0) reaches (4, 0) after ±π, not π/2
  EXPECT_EQ(mesh_error(arc).first, MeshError::Value::arc_sweep);
  EXPECT_EQ(mesh_error(arc).second.rfind("the sweep from the start node does not end at the end node (", 0), 0u);
  arc.arc = Arc{{2, 0}, -pi};  // reaches it: no error
  EXPECT_EQ(mesh_error(arc).second, "no error");
}

TEST(MemberMesh, LumpsADistributedLoadHalfToEachEndOfEveryElement) {
  // A beam (0, 0)–(4, 0) in 4 elements under w = −10 per unit length: each element carries −10
  // and gives −5 to each end, so the interior nodes take −10 and the ends −5 (total wL = −40).
  // An inclined bar (0, 0)–(3, 4), 5 long, in one element under fx = 2: 5 to each end.
  Model model = nodes_only({{1, {0, 0}}, {2, {4, 0}}, {3, {3, 4}}}, 5.0);
  MemberMesh mesh(model);
  MemberInput beam = member(0, 1, 4);
  beam.load = {0.0, -10.0};
  mesh.add(beam);
  MemberInput bar = member(0, 2, 1);
  bar.load = {2.0, 0.0};
  mesh.add(bar);
  mesh.finish();
  const auto fy = [&](int node) { return model.reference_load[3 * node + tsm::uy]; };
  const auto fx = [&](int node) { return model.reference_load[3 * node + tsm::ux]; };
  EXPECT_DOUBLE_EQ(fy(0), -5.0);
  EXPECT_DOUBLE_EQ(fy(1), -5.0);
  for (int node = 3; node <= 5; ++node) EXPECT_DOUBLE_EQ(fy(node), -10.0) << node;  // the generated ones
  EXPECT_DOUBLE_EQ(fx(0), 5.0);
  EXPECT_DOUBLE_EQ(fx(2), 5.0);
  EXPECT_EQ(fx(1), 0.0);
  EXPECT_EQ(model.reference_load[3 * 0 + tsm::rz], 0.0);
  // The loaded beam's middle node, (2, 0), is the second one generated; the one-element bar has none.
  ASSERT_EQ(mesh.loaded_middles().size(), 1u);
  EXPECT_EQ(model.nodes[mesh.loaded_middles()[0]].position, Eigen::Vector2d(2, 0));
}

TEST(MemberMesh, KeepsPressureAndEndSpringsPerMemberOnlyWhereSomeMemberHasThem) {
  Model model = nodes_only({{1, {0, 0}}, {2, {1, 0}}, {3, {2, 0}}}, 2.0);
  MemberMesh mesh(model);
  mesh.add(member(0, 1, 1));
  MemberInput sprung = member(1, 2, 1);
  sprung.pressure = 3.0;
  sprung.flexibility_to = 0.25;
  mesh.add(sprung);
  mesh.add(member(2, 0, 1));
  mesh.finish();
  ASSERT_EQ(model.member_extras.size(), 3u);
  EXPECT_EQ(model.pressure(model.elements[0]), 0.0);
  EXPECT_EQ(model.pressure(model.elements[1]), 3.0);
  EXPECT_EQ(model.flexibility_end(model.elements[1]), 0.25);
  EXPECT_EQ(model.flexibility_start(model.elements[1]), 0.0);

  Model plain = nodes_only({{1, {0, 0}}, {2, {1, 0}}}, 1.0);
  MemberMesh plain_mesh(plain);
  plain_mesh.add(member(0, 1, 2));
  plain_mesh.finish();
  EXPECT_TRUE(plain.member_extras.empty());
}

TEST(FixFreeRotations, FixesTheRotationOfAHingeAndOfANodeNoElementHolds) {
  // Members 1 → 2 (hinged at its end) and 2 → 3 (hinged at its start): node 2 turns with no
  // element end. Member 3 → 4 is hinged at 3 too, but 2 → 3 holds node 3 rigidly: it keeps its
  // rotation. Node 5 is held by no element.
  Model model = nodes_only({{1, {0, 0}}, {2, {1, 0}}, {3, {2, 0}}, {4, {3, 0}}, {5, {0, 5}}}, 6.0);
  MemberMesh mesh(model);
  MemberInput left = member(0, 1, 1), right = member(1, 2, 1), third = member(2, 3, 1);
  left.release_end = true;
  right.release_start = true;
  third.release_start = true;
  mesh.add(left);
  mesh.add(right);
  mesh.add(third);
  mesh.finish();
  tsm::fix_free_rotations(model);
  const auto fixed = [&](int node) { return static_cast<bool>(model.constrained[3 * node + tsm::rz]); };
  EXPECT_FALSE(fixed(0));
  EXPECT_TRUE(fixed(1));
  EXPECT_FALSE(fixed(2));
  EXPECT_FALSE(fixed(3));
  EXPECT_TRUE(fixed(4));
  EXPECT_FALSE(model.constrained[3 * 1 + tsm::ux] || model.constrained[3 * 1 + tsm::uy]);
}

TEST(DefaultMonitor, ShowsTheNodesLoadsAndPrescribedDisplacementsNameElseTheLoadedMembersMiddles) {
  Model model = nodes_only({{1, {0, 0}}, {2, {1, 0}}, {3, {2, 0}}, {4, {3, 0}}}, 3.0);
  model.reference_prescribed = Eigen::VectorXd::Zero(12);
  EXPECT_EQ(tsm::default_monitor(model, {2}, {1}), std::vector<int>{2});
  model.reference_prescribed[3 * 3 + tsm::uy] = 0.1;
  EXPECT_EQ(tsm::default_monitor(model, {2}, {1}), (std::vector<int>{2, 3}));
  model.reference_prescribed.setZero();
  EXPECT_EQ(tsm::default_monitor(model, {}, {1, 2, 1}), (std::vector<int>{1, 2}));
  EXPECT_TRUE(tsm::default_monitor(model, {}, {}).empty());
}

}  // namespace
