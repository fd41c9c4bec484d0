// Point loads along members ("loads": {"member": k, "at": fraction, …}; issue 29): the mesh puts a
// node at the load's station (a division point where it falls on one), so the load acts at a
// material point and rides with the member when it turns. Against the closed form of a simply
// supported beam under an off-node load; against the same structure drawn with a node there
// (large rotation, follower and fixed-direction loads); on an arc; in a stage; bad input.
#include <gtest/gtest.h>

#include <cmath>

#include "support/models.hpp"

namespace test_member_point_loads {
namespace {

using namespace tsm::test;

constexpr double E = 2e11, I = 1e-4, A = 1e-2, L = 4.0;

json steel_beam(int divisions) {
  return {{"materials", {{"steel", {{"E", E}}}}},
          {"sections", {{"s", {{"A", A}, {"I", I}}}}},
          {"nodes", json::array({{{"id", 1}, {"x", 0.0}, {"y", 0.0}}, {{"id", 2}, {"x", L}, {"y", 0.0}}})},
          {"members", json::array({{{"from", 1}, {"to", 2}, {"divisions", divisions}, {"material", "steel"}, {"section", "s"}}})},
          {"analysis", {{"tolerance", 1e-12}}}};
}

/// The index of the node at (x, y), −1 if none.
int node_at(const tsm::Model& model, double x, double y) {
  for (int k = 0; k < model.node_count(); ++k)
    if ((model.nodes[k].position - Eigen::Vector2d(x, y)).norm() < 1e-12) return k;
  return -1;
}

TEST(MemberPointLoads, ASimplySupportedBeamDeflectsUnderAnOffNodeLoadAsTheClosedFormSays) {
  // P at a = 0.3 L, between the division points of 4 elements: v = P a² b² / (3 EI L) there,
  // the supports carry P b/L and P a/L. Small load: the geometry's share is ~1e-7.
  const double P = -1e3, a = 0.3 * L, b = L - a;
  json m = steel_beam(4);
  m["supports"] = json::array({{{"node", 1}, {"type", "pinned"}}, {{"node", 2}, {"type", "roller-x"}}});
  m["loads"] = json::array({{{"member", 0}, {"at", 0.3}, {"fy", P}}});
  tsm::Model model;
  const tsm::solver::RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  EXPECT_EQ(model.elements.size(), 5u);  // the element holding the station split in two
  const int at = node_at(model, a, 0.0);
  ASSERT_GE(at, 0);
  EXPECT_NEAR(r.steps.back().displacements[3 * at + 1] / (P * a * a * b * b / (3.0 * E * I * L)), 1.0, 1e-6);
  EXPECT_NEAR(r.steps.back().reactions[1], -P * b / L, 1e-9 * std::abs(P));
  EXPECT_NEAR(r.steps.back().reactions[4], -P * a / L, 1e-9 * std::abs(P));
  // A load at a division point uses that node: no element is added.
  m["loads"][0]["at"] = 0.5;
  EXPECT_EQ(tsm::io::read_model(m).elements.size(), 4u);
}

TEST(MemberPointLoads, ALoadAlongAMemberRidesWithItAsAtANodeDrawnThere) {
  // A cantilever (EI 1) under a load at its middle large enough to turn it 0.65–0.73 rad, its member
  // in 3 divisions (so the middle is a station of its own), against the same nodes drawn as
  // four one-element members with the load on the middle node: equal to rounding.
  for (const bool follower : {false, true}) {
    json m = beam_model({.divisions = 3});
    m["supports"] = json::array({{{"node", 1}, {"type", "fixed"}}});
    m["loads"] = json::array({{{"member", 0}, {"at", 0.5}, {"fy", 6.0}, {"follower", follower}}});
    m["analysis"] = {{"control", {{"type", "load"}, {"steps", 4}}}, {"tolerance", 1e-12}};
    json drawn = m;
    drawn["nodes"] = json::array({{{"id", 1}, {"x", 0.0}, {"y", 0.0}}, {{"id", 3}, {"x", 1.0 / 3.0}, {"y", 0.0}},
                                  {{"id", 4}, {"x", 0.5}, {"y", 0.0}}, {{"id", 5}, {"x", 2.0 / 3.0}, {"y", 0.0}},
                                  {{"id", 2}, {"x", 1.0}, {"y", 0.0}}});
    drawn["members"] = json::array();
    for (const auto& [from, to] : std::vector<std::pair<int, int>>{{1, 3}, {3, 4}, {4, 5}, {5, 2}}) {
      json member = m["members"][0];
      member["from"] = from, member["to"] = to, member["divisions"] = 1;
      drawn["members"].push_back(member);
    }
    drawn["loads"] = json::array({{{"node", 4}, {"fy", 6.0}, {"follower", follower}}});
    tsm::Model along, at_node;
    const tsm::solver::RunResult a = run(m, along), b = run(drawn, at_node);
    ASSERT_EQ(a.status, tsm::solver::Status::converged) << a.message;
    ASSERT_EQ(b.status, tsm::solver::Status::converged) << b.message;
    const Eigen::Vector3d tip_a = node_displacement(along, a.steps.back(), 2), tip_b = node_displacement(at_node, b.steps.back(), 2);
    EXPECT_GT(std::abs(tip_a[2]), 0.6) << "turned";
    EXPECT_LT((tip_a - tip_b).norm(), 1e-10) << (follower ? "follower" : "fixed direction");
    const int middle = node_at(along, 0.5, 0.0);
    ASSERT_GE(middle, 0);
    EXPECT_LT((a.steps.back().displacements.segment<3>(3 * middle) - node_displacement(at_node, b.steps.back(), 4)).norm(), 1e-10);
  }
}

TEST(MemberPointLoads, OnAnArcTheStationIsOnTheCircle) {
  json m = steel_beam(4);
  m["nodes"][1] = {{"id", 2}, {"x", 1.0}, {"y", 1.0}};
  m["nodes"][0] = {{"id", 1}, {"x", 0.0}, {"y", 0.0}};
  m["members"][0]["arc"] = {{"center", {1.0, 0.0}}, {"sweep", -M_PI / 2}};  // from (0, 0) clockwise to (1, 1)
  m["supports"] = json::array({{{"node", 1}, {"type", "fixed"}}});
  m["loads"] = json::array({{{"member", 0}, {"at", 0.4}, {"fy", -1.0}}});
  const tsm::Model model = tsm::io::read_model(m);
  const double angle = M_PI - 0.4 * M_PI / 2;
  EXPECT_GE(node_at(model, 1.0 + std::cos(angle), std::sin(angle)), 0);
  EXPECT_EQ(model.elements.size(), 5u);
}

TEST(MemberPointLoads, AStageMayLoadAMemberAlongItsLength) {
  json m = steel_beam(2);
  m["supports"] = json::array({{{"node", 1}, {"type", "fixed"}}});
  m["stages"] = json::array({{{"loads", json::array({{{"member", 0}, {"at", 0.25}, {"fy", -100.0}}})}}});
  tsm::Model model;
  const tsm::solver::RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  EXPECT_NEAR(r.steps.back().reactions[1], 100.0, 1e-9);
  EXPECT_NEAR(r.steps.back().reactions[2], 100.0 * 0.25 * L, 1e-6);
}

TEST(MemberPointLoads, TheReaderRefusesAStationThatIsNone) {
  json m = steel_beam(2);
  m["supports"] = json::array({{{"node", 1}, {"type", "fixed"}}});
  m["loads"] = json::array({{{"member", 0}, {"at", 1.0}, {"fy", 1.0}}});
  EXPECT_NE(refusal(m).find("loads[0].at: must lie between 0 and 1"), std::string::npos) << refusal(m);
  m["loads"][0]["at"] = 0.0;
  EXPECT_NE(refusal(m).find("loads[0].at: must lie between 0 and 1"), std::string::npos) << refusal(m);
  m["loads"][0] = {{"member", 3}, {"at", 0.5}, {"fy", 1.0}};
  EXPECT_NE(refusal(m).find("loads[0].member: unknown member 3"), std::string::npos) << refusal(m);
  m["loads"][0] = {{"at", 0.5}, {"fy", 1.0}};
  EXPECT_NE(refusal(m).find("loads[0].member: missing"), std::string::npos) << refusal(m);
  m["loads"][0] = {{"node", 2}, {"member", 0}, {"at", 0.5}, {"fy", 1.0}};
  EXPECT_NE(refusal(m).find("loads[0]: give \"node\", or \"member\" and \"at\", not both"), std::string::npos) << refusal(m);
}

}  // namespace

}  // namespace test_member_point_loads
