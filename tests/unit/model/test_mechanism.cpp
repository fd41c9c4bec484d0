// The mechanism check (model/mechanism.hpp) on models built by hand: a node no element holds,
// a part's free translation or rotation (its pole), a fixed rotation at a hinge holding nothing,
// and contacts resting as drawn holding a part — by supports, or through a part that is held,
// either way round — against motions worked out by hand.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "tsmframe/model/mechanism.hpp"

namespace {

using tsm::Model;

// Nodes (ids 1, 2, … in the given order) and elements, each its own member; nothing supported.
Model frame(const std::vector<Eigen::Vector2d>& positions, const std::vector<std::pair<int, int>>& elements) {
  Model model;
  Eigen::Vector2d lo = positions.front(), hi = lo;
  for (size_t k = 0; k < positions.size(); ++k) {
    model.nodes.push_back({static_cast<int>(k) + 1, positions[k]});
    lo = lo.cwiseMin(positions[k]);
    hi = hi.cwiseMax(positions[k]);
  }
  model.size = (hi - lo).norm();
  for (const auto& [start, end] : elements) {
    tsm::Element e;
    e.id = static_cast<int>(model.elements.size()) + 1;
    e.start = start;
    e.end = end;
    e.member = static_cast<int>(model.elements.size());
    model.elements.push_back(e);
  }
  model.member_count = static_cast<int>(elements.size());
  model.constrained.assign(tsm::dofs_per_node * positions.size(), false);
  return model;
}

void fix(Model& model, int node, std::initializer_list<tsm::Dof> dofs) {
  for (const tsm::Dof dof : dofs) model.constrained[tsm::dofs_per_node * node + dof] = true;
}

void contact(Model& model, int node, int member, double gap) {
  tsm::ContactSpec c;
  c.node = node;
  c.members = {member};
  c.gap = gap;
  model.contacts.push_back(c);
}

// The pole in "… free to rotate about (x, y) …".
Eigen::Vector2d pole_in(const std::string& message) {
  const size_t at = message.find("rotate about (");
  Eigen::Vector2d pole(NAN, NAN);
  if (at != std::string::npos) std::sscanf(message.c_str() + at, "rotate about (%lf, %lf)", &pole.x(), &pole.y());
  return pole;
}

const std::string free_part_one = "structure is a mechanism: the part holding node 1 and the 1 node joined to it is free to ";

TEST(MechanismCheck, AFixedCantileverIsNoMechanism) {
  Model model = frame({{0, 0}, {2, 0}}, {{0, 1}});
  fix(model, 0, {tsm::ux, tsm::uy, tsm::rz});
  EXPECT_FALSE(tsm::find_mechanism(model));
}

TEST(MechanismCheck, ABeamOnTwoRollersAcrossItMovesAlongIt) {
  // uy fixed at both ends stops the translation along y and the rotation; x is free.
  Model model = frame({{0, 0}, {2, 0}}, {{0, 1}});
  fix(model, 0, {tsm::uy});
  fix(model, 1, {tsm::uy});
  EXPECT_EQ(tsm::find_mechanism(model).value_or(""), free_part_one + "move along x (no support fixes ux)");
}

TEST(MechanismCheck, AnUprightHeldAlongXAtBothEndsMovesAlongY) {
  Model model = frame({{5, 0}, {5, 2}}, {{0, 1}});
  fix(model, 0, {tsm::ux});
  fix(model, 1, {tsm::ux});
  EXPECT_EQ(tsm::find_mechanism(model).value_or(""), free_part_one + "move along y (no support fixes uy)");
}

TEST(MechanismCheck, APartPinnedAtOneNodeRotatesAboutThePin) {
  // The pin at (3, 1) stops both translations there: the part turns about it.
  Model model = frame({{1, 1}, {3, 1}}, {{0, 1}});
  fix(model, 1, {tsm::ux, tsm::uy});
  const std::string message = tsm::find_mechanism(model).value_or("");
  EXPECT_EQ(message.rfind(free_part_one + "rotate about (", 0), 0u) << message;
  EXPECT_NE(message.find(") (add a support that stops it)"), std::string::npos) << message;
  const Eigen::Vector2d pole = pole_in(message);
  EXPECT_NEAR(pole.x(), 3.0, 1e-9) << message;
  EXPECT_NEAR(pole.y(), 1.0, 1e-9) << message;
}

TEST(MechanismCheck, AFixedRotationWhereEveryElementEndIsHingedHoldsNothing) {
  // A bar hinged at both ends, its start fixed in all three dofs: the fixed rotation does not
  // turn the bar, which turns about the start; without the hinges the start clamps it.
  Model model = frame({{0, 0}, {2, 0}}, {{0, 1}});
  fix(model, 0, {tsm::ux, tsm::uy, tsm::rz});
  model.elements[0].release_start = model.elements[0].release_end = true;
  const std::string message = tsm::find_mechanism(model).value_or("");
  EXPECT_EQ(message.rfind(free_part_one + "rotate about (", 0), 0u) << message;
  EXPECT_NEAR(pole_in(message).x(), 0.0, 1e-9) << message;
  EXPECT_NEAR(pole_in(message).y(), 0.0, 1e-9) << message;
  model.elements[0].release_start = false;
  EXPECT_FALSE(tsm::find_mechanism(model));
}

TEST(MechanismCheck, ANodeNoElementHoldsIsNamedWithItsFirstFreeDof) {
  // A clamped cantilever and node 3 beside it, its ux fixed only.
  Model model = frame({{0, 0}, {2, 0}, {5, 5}}, {{0, 1}});
  fix(model, 0, {tsm::ux, tsm::uy, tsm::rz});
  fix(model, 2, {tsm::ux});
  EXPECT_EQ(tsm::find_mechanism(model).value_or(""),
            "structure is a mechanism: node 3 is held by no element and its uy is not supported");
  fix(model, 2, {tsm::uy});
  EXPECT_EQ(tsm::find_mechanism(model).value_or(""),
            "structure is a mechanism: node 3 is held by no element and its rz is not supported");
  fix(model, 2, {tsm::rz});
  EXPECT_FALSE(tsm::find_mechanism(model));
}

TEST(MechanismCheck, ABeamOnTwoKnifeEdgesAtItsGapIsHeldByThemAlone) {
  // A beam (0, 0)–(4, 0), its ux fixed at the start; two fixed knife edges 0.05 below it at
  // x = 1 and 3, contacts with gap 0.05: they hold y and the rotation, the support x.
  Model model = frame({{0, 0}, {4, 0}, {1, -0.05}, {3, -0.05}}, {{0, 1}});
  fix(model, 0, {tsm::ux});
  for (const int knife : {2, 3}) {
    fix(model, knife, {tsm::ux, tsm::uy, tsm::rz});
    contact(model, knife, 0, 0.05);
  }
  EXPECT_FALSE(tsm::find_mechanism(model));
  const std::string message = tsm::find_mechanism(model, false).value_or("");
  EXPECT_EQ(message.rfind(free_part_one, 0), 0u) << "held only by the contacts: " << message;
  // The same answers without the sentence (solver::TsmProblem asks at every run's set-up).
  EXPECT_FALSE(tsm::is_mechanism(model));
  EXPECT_TRUE(tsm::is_mechanism(model, false));
}

TEST(MechanismCheck, ANodeDrawnAtItsGapOverAConvexCornerIsToldItRestsOnNeitherElement) {
  // A roof of two held elements meeting at (0, 1), a plank (−1, 1.1)–(1, 1.1) held along x and
  // in rotation, its middle node (0, 1.1) a contact at gap 0.1 over the apex: 0.1 from the beam
  // node, but beside both elements' spans (the roof turns away from it). The plank's ends, also
  // contacts, are drawn far above the roof: the apex node is the one meant to rest, and named.
  Model model = frame({{-2, 0}, {0, 1}, {2, 0}, {-1, 1.1}, {0, 1.1}, {1, 1.1}}, {{0, 1}, {1, 2}, {3, 4}, {4, 5}});
  for (const int held : {0, 1, 2}) fix(model, held, {tsm::ux, tsm::uy, tsm::rz});
  fix(model, 4, {tsm::ux, tsm::rz});
  model.elements[3].member = 2;  // the plank is one member
  model.elements[1].member = 0;  // and the roof another
  model.member_count = 3;
  for (const int node : {3, 4, 5}) contact(model, node, 0, 0.1);
  const std::string message = tsm::find_mechanism(model).value_or("");
  EXPECT_NE(message.find("contact node 5 is drawn 0.1 from beam node 2, within its gap 0.1, but beside both elements"),
            std::string::npos)
      << message;
}

TEST(MechanismCheck, ABeamLyingOnAHeldBeamIsHeldByItAndSlidesWithoutAnAxialSupport) {
  // A simply supported beam (0, 0)–(4, 0); a second beam (1, 0.05)–(3, 0.05) lying on it, its
  // two nodes contacts on the first with gap 0.05. The lower beam holds the upper one in y and
  // in rotation; the upper one's ux at its start holds the rest.
  Model model = frame({{0, 0}, {4, 0}, {1, 0.05}, {3, 0.05}}, {{0, 1}, {2, 3}});
  fix(model, 0, {tsm::ux, tsm::uy});
  fix(model, 1, {tsm::uy});
  contact(model, 2, 0, 0.05);
  contact(model, 3, 0, 0.05);
  Model sliding = model;
  fix(model, 2, {tsm::ux});
  EXPECT_FALSE(tsm::find_mechanism(model));
  // Without it the upper beam slides along x (frictionless contacts); its contacts rest as
  // drawn, so the message says when a contact holds and names none that plainly does not.
  EXPECT_EQ(tsm::find_mechanism(sliding).value_or(""),
            "structure is a mechanism: the part holding node 3 and the 1 node joined to it is free to move along x "
            "(no support fixes ux); a contact holds it from the start only if its node is drawn at the contact's "
            "\"gap\" from the beam's centre line, on the side it supports, and the node or the beam is held (by "
            "supports, or by a part that is)");
}

TEST(MechanismCheck, APartHeldOnlyThroughAnotherHeldPartIsHeld) {
  // The lower beam (0, 0)–(4, 0) has only its ux fixed. The upper beam (1, 0.05)–(3, 0.05) is
  // clamped at its start and rests on the lower one at both nodes: at the clamped node from the
  // start, at the free end once the upper beam is known to be held — the second pass of the check.
  Model model = frame({{0, 0}, {4, 0}, {1, 0.05}, {3, 0.05}}, {{0, 1}, {2, 3}});
  fix(model, 0, {tsm::ux});
  fix(model, 2, {tsm::ux, tsm::uy, tsm::rz});
  contact(model, 2, 0, 0.05);
  contact(model, 3, 0, 0.05);
  EXPECT_FALSE(tsm::find_mechanism(model));
  EXPECT_TRUE(tsm::find_mechanism(model, false));
  // One resting contact alone leaves the lower beam free to turn about its touch point (1, 0).
  model.contacts.pop_back();
  const std::string message = tsm::find_mechanism(model).value_or("");
  EXPECT_EQ(message.rfind(free_part_one + "rotate about (", 0), 0u) << message;
  EXPECT_NEAR(pole_in(message).x(), 1.0, 1e-9) << message;
  EXPECT_NEAR(pole_in(message).y(), 0.0, 1e-9) << message;
}

// SupportedParts at a displaced state, against motions and second-order work worked out by hand.
// A bent beam (0, 0)–(1, 1)–(2, 0) on a pin at node 1 and a roller along x at node 3.
Model pin_and_roller() {
  Model model = frame({{0, 0}, {1, 1}, {2, 0}}, {{0, 1}, {1, 2}});
  fix(model, 0, {tsm::ux, tsm::uy});
  fix(model, 2, {tsm::uy});
  return model;
}

/// Displacements of every dof moving node `node` by (dx, dy).
Eigen::VectorXd moved(const Model& model, int node, double dx, double dy) {
  Eigen::VectorXd d = Eigen::VectorXd::Zero(model.dof_count());
  d[tsm::dofs_per_node * node + tsm::ux] = dx;
  d[tsm::dofs_per_node * node + tsm::uy] = dy;
  return d;
}

TEST(SupportedParts, ARollerBroughtOntoThePinLetsThePartTurnAboutIt) {
  const Model model = pin_and_roller();
  const tsm::SupportedParts parts(model);
  const Eigen::VectorXd none = Eigen::VectorXd::Zero(model.dof_count());
  EXPECT_FALSE(parts.neutral_motion(none, none));  // as drawn the roller stops the turn
  EXPECT_FALSE(parts.neutral_motion(moved(model, 2, -1.9, 0.0), none));  // 0.1 off the pin: still
  const Eigen::VectorXd closed = moved(model, 2, -2.0, 0.0);
  Eigen::VectorXd moments = none;  // end moments alone (the ring's loads): no work on the turn
  moments[tsm::rz] = -5.0;
  moments[2 * tsm::dofs_per_node + tsm::rz] = 5.0;
  const auto motion = parts.neutral_motion(closed, moments);
  ASSERT_TRUE(motion);
  EXPECT_EQ(motion->kind, tsm::FreeMotion::Kind::rotation);
  EXPECT_NEAR(motion->pole.x(), 0.0, 1e-9);
  EXPECT_NEAR(motion->pole.y(), 0.0, 1e-9);
  EXPECT_EQ(motion->node, 0);
  EXPECT_EQ(motion->part_nodes, 3);
  EXPECT_EQ(tsm::part_text(model, *motion), "the part holding node 1 and the 2 nodes joined to it");
  EXPECT_EQ(tsm::motion_text(*motion), "rotate about (0, 0)");
}

TEST(SupportedParts, APendulumsLoadHoldsItsTurnSoItIsNotNeutral) {
  // A bar hanging from a pin at (0, 0) to (0, −2): the pin leaves the turn about it free, and the
  // weight W at the lower end does the work W·2·φ²/2 on it (Σ r·f = (0, −2)·(0, −W) = 2W): the
  // tangent is not singular along it. Without the weight the turn is neutral.
  Model model = frame({{0, 0}, {0, -2}}, {{0, 1}});
  fix(model, 0, {tsm::ux, tsm::uy});
  const tsm::SupportedParts parts(model);
  const Eigen::VectorXd none = Eigen::VectorXd::Zero(model.dof_count());
  Eigen::VectorXd weight = none;
  weight[tsm::dofs_per_node + tsm::uy] = -3.0;  // the internal force at the lower end: the load
  weight[tsm::uy] = 3.0;                         // and the pin's reaction (no work: r = 0)
  EXPECT_FALSE(parts.neutral_motion(none, weight));
  const auto unloaded = parts.neutral_motion(none, none);
  ASSERT_TRUE(unloaded);
  EXPECT_EQ(unloaded->kind, tsm::FreeMotion::Kind::rotation);
  // Round-off in a converged state's forces leaves it neutral: 1e-9 of the weight.
  weight *= 1e-9 / 3.0;
  weight[tsm::rz] = 1.0;  // a moment sets the forces' scale
  EXPECT_TRUE(parts.neutral_motion(none, weight));
}

TEST(SupportedParts, AFreeTranslationIsAlwaysNeutralAndASpringHoldsIt) {
  Model model = frame({{0, 0}, {2, 0}}, {{0, 1}});
  fix(model, 0, {tsm::uy});
  fix(model, 1, {tsm::uy});
  const Eigen::VectorXd none = Eigen::VectorXd::Zero(model.dof_count());
  Eigen::VectorXd pushed = none;  // a force along the free direction does no work on a translation
  pushed[tsm::ux] = 4.0;
  const auto motion = tsm::SupportedParts(model).neutral_motion(none, pushed);
  ASSERT_TRUE(motion);
  EXPECT_EQ(motion->kind, tsm::FreeMotion::Kind::translation);
  EXPECT_EQ(tsm::motion_text(*motion), "move along x");
  model.springs.push_back({1, tsm::NodalSpring::Kind::translation, Eigen::Vector2d::UnitX(), 100.0});
  EXPECT_FALSE(tsm::SupportedParts(model).neutral_motion(none, pushed));
}

}  // namespace
