// Member releases (hinges, "release" on a member): the von Mises truss with real pins against its
// closed form through the snap-through; a three-hinged arch's thrust against statics; a clamped
// column hinged at its ends buckling as a pinned one; the reader's checks (a moment at a hinge,
// cantilever-frame contacts on hinged members, a bar left free to turn); a contact next to an
// inner hinge and sliding through it, against the Gerber beam's closed form. Semi-rigid connections ("end_springs"): a
// clamped beam on end springs against slope-deflection, a cantilever whose root spring turns as
// far as the beam bends (two full turns at its tip, its tip back on the root), the reader's checks.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>

#include "support/models.hpp"
#include "tsmframe/io/model_reader.hpp"
#include "tsmframe/io/results_writer.hpp"
#include "tsmframe/solver/unloaded_mechanism.hpp"

namespace {

using namespace tsm::test;
using tsm::solver::RunResult;
using tsm::solver::StepRecord;

// Two bars of EA = 1 pinned at both ends (I = 1: the hinges, not a vanishing I, make them bars),
// half-span 1, rise 0.1, apex driven down: P(w) = 2 EA (L0 − L)/L0 · (h − w)/L.
TEST(Hinges, AVonMisesTrussOfPinnedBarsFollowsItsClosedFormThroughTheSnapThrough) {
  const double rise = 0.1, load = 1e-3;
  const json m = {
      {"materials", {{"m", {{"E", 1.0}}}}},
      {"sections", {{"s", {{"A", 1.0}, {"I", 1.0}}}}},
      {"nodes", json::array({{{"id", 1}, {"x", 0.0}, {"y", 0.0}}, {{"id", 2}, {"x", 1.0}, {"y", rise}},
                             {{"id", 3}, {"x", 2.0}, {"y", 0.0}}})},
      {"members", json::array({{{"from", 1}, {"to", 2}, {"material", "m"}, {"section", "s"}, {"release", "both"}},
                               {{"from", 2}, {"to", 3}, {"material", "m"}, {"section", "s"}, {"release", "both"}}})},
      {"supports", json::array({{{"node", 1}, {"type", "pinned"}}, {{"node", 3}, {"type", "pinned"}}})},
      {"loads", json::array({{{"node", 2}, {"fy", -load}}})},
      {"analysis", {{"control", {{"type", "displacement"}, {"node", 2}, {"dof", "uy"}, {"target", -0.25}, {"steps", 10}}},
                    {"output", "all"}}},
  };
  tsm::Model model;
  const RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  ASSERT_EQ(r.steps.size(), 10u);
  const double L0 = std::hypot(1.0, rise);
  for (const StepRecord& s : r.steps) {
    const double w = -node_displacement(model, s, 2)[1], L = std::hypot(1.0, rise - w);
    const double exact = 2.0 * (L0 - L) / L0 * (rise - w) / L;
    EXPECT_NEAR(load * s.load_factor, exact, 1e-12 * 0.4) << "w " << w;
    for (int e = 0; e < 2; ++e)  // bars: no end moments
      EXPECT_EQ(s.element_forces.segment<2>(3 * e + 1).norm(), 0.0) << "element " << e;
  }
  ASSERT_EQ(r.limit_points.size(), 2u);  // the maximum and the minimum of the snap-through
  // Allowed one iterate, a load step fails; its bars (a section "deeper" than they are long) do
  // not bend, so the failure does not blame short Euler–Bernoulli elements.
  json past = m;
  past["analysis"] = {{"control", {{"type", "load"}, {"steps", 1}}}, {"cutback", false}, {"max_iterations", 1}};
  past["loads"][0]["fy"] = -3e-4;
  tsm::Model model_past;
  const RunResult failed = run(past, model_past);
  ASSERT_NE(failed.status, tsm::solver::Status::converged);
  EXPECT_EQ(failed.message.find("Euler–Bernoulli element"), std::string::npos) << failed.message;
}

// A three-hinged arch: two straight members from pinned supports at (0, 0) and (10, 0) meeting
// in a hinge at the crown (5, 2). Statically determinate: a crown load P gives the supports P/2
// each upward and a thrust H = P L / (4 h) = 1250 for P = 1000 (linear: a stiff arch, a small load).
json three_hinged_arch(double P) {
  return json{{"materials", {{"s", {{"E", 2e11}}}}},
              {"sections", {{"x", {{"A", 0.01}, {"I", 1e-4}}}}},
              {"nodes", json::array({{{"id", 1}, {"x", 0.0}, {"y", 0.0}}, {{"id", 2}, {"x", 5.0}, {"y", 2.0}},
                                     {{"id", 3}, {"x", 10.0}, {"y", 0.0}}})},
              {"members", json::array({{{"from", 1}, {"to", 2}, {"divisions", 10}, {"material", "s"}, {"section", "x"},
                                        {"release", "end"}},
                                       {{"from", 2}, {"to", 3}, {"divisions", 10}, {"material", "s"}, {"section", "x"},
                                        {"release", "start"}}})},
              {"supports", json::array({{{"node", 1}, {"type", "pinned"}}, {{"node", 3}, {"type", "pinned"}}})},
              {"loads", json::array({{{"node", 2}, {"fy", -P}}})},
              {"analysis", {{"control", {{"type", "load"}, {"steps", 1}}}}}};
}

TEST(Hinges, AThreeHingedArchCarriesItsCrownLoadWithTheThrustOfStatics) {
  const double P = 1000.0, H = P * 10.0 / (4.0 * 2.0);
  tsm::Model model;
  const RunResult r = run(three_hinged_arch(P), model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  const StepRecord& last = r.steps.back();
  const Eigen::Vector3d left = last.reactions.segment<3>(3 * model.node_index(1));
  const Eigen::Vector3d right = last.reactions.segment<3>(3 * model.node_index(3));
  EXPECT_NEAR(left[0], H, 1e-4 * H);  // the arch pushes out, the support pushes in
  EXPECT_NEAR(right[0], -H, 1e-4 * H);
  EXPECT_NEAR(left[1], P / 2.0, 1e-6 * P);
  EXPECT_NEAR(right[1], P / 2.0, 1e-6 * P);
  // No moment at the hinges (crown: the last element of member 0, the first of member 1) and
  // at the pinned feet; a straight member between hinges carries only N.
  EXPECT_EQ(last.element_forces[3 * 9 + 2], 0.0);
  EXPECT_EQ(last.element_forces[3 * 10 + 1], 0.0);
  for (int e = 0; e < 20; ++e) EXPECT_LE(std::abs(last.element_forces[3 * e + 1]), 1e-6 * P) << "element " << e;
  expect_global_equilibrium(model, last);
  // results.json names the hinged elements' ends.
  std::ostringstream out;
  tsm::io::write_results_json(out, model, r);
  const json written = json::parse(out.str());
  EXPECT_EQ(written["elements"][9]["release"], "end");
  EXPECT_EQ(written["elements"][10]["release"], "start");
  EXPECT_FALSE(written["elements"][0].contains("release"));
  // Reactions: the two feet, not the crown, whose rotation the reader fixed (a hinge is no support).
  ASSERT_EQ(written["steps"][0]["reactions"].size(), 2u) << written["steps"][0]["reactions"].dump();
  EXPECT_TRUE(written["steps"][0]["reactions"].contains("1"));
  EXPECT_TRUE(written["steps"][0]["reactions"].contains("3"));
}

TEST(Hinges, AColumnHingedAtItsClampedEndsBucklesAsAPinnedOne) {
  // 1.2 times the Euler load with a small side push at mid-height, far into the post-buckling
  // range: hinges at the ends of a column whose ends are clamped (rotation fixed) give the
  // pinned column's path — the supports' rotations hold nothing through a hinge.
  const double E = 2e11, I = 1e-6, L = 5.0, Pcr = std::pow(std::acos(-1.0), 2) * E * I / (L * L);
  json m = {{"materials", {{"s", {{"E", E}}}}},
            {"sections", {{"x", {{"A", 1e-3}, {"I", I}}}}},
            {"nodes", json::array({{{"id", 1}, {"x", 0.0}, {"y", 0.0}}, {{"id", 2}, {"x", 0.0}, {"y", L}},
                                   {{"id", 3}, {"x", 0.0}, {"y", L / 2}}})},
            {"members", json::array({{{"from", 1}, {"to", 3}, {"divisions", 10}, {"material", "s"}, {"section", "x"}},
                                     {{"from", 3}, {"to", 2}, {"divisions", 10}, {"material", "s"}, {"section", "x"}}})},
            {"loads", json::array({{{"node", 2}, {"fy", -1.2 * Pcr}}, {{"node", 3}, {"fx", 1e-3 * Pcr}}})},
            {"analysis", {{"control", {{"type", "load"}, {"steps", 20}}}}}};
  json pinned = m, hinged = m;
  pinned["supports"] = json::array({{{"node", 1}, {"type", "pinned"}}, {{"node", 2}, {"type", "roller-y"}}});
  hinged["supports"] = json::array({{{"node", 1}, {"type", "fixed"}}, {{"node", 2}, {"fix", {"ux", "rz"}}}});
  hinged["members"][0]["release"] = "start";
  hinged["members"][1]["release"] = "end";
  tsm::Model a, b;
  const RunResult ra = run(pinned, a), rb = run(hinged, b);
  ASSERT_EQ(ra.status, tsm::solver::Status::converged) << ra.message;
  ASSERT_EQ(rb.status, tsm::solver::Status::converged) << rb.message;
  const Eigen::Vector3d mid_a = node_displacement(a, ra.steps.back(), 3), mid_b = node_displacement(b, rb.steps.back(), 3);
  EXPECT_GT(std::abs(mid_a[0]), 0.25 * L);  // buckled far
  EXPECT_NEAR(mid_b[0], mid_a[0], 1e-9 * L);
  EXPECT_NEAR(mid_b[1], mid_a[1], 1e-9 * L);
}

TEST(Hinges, TheReaderChecksWhatAHingeCannotDo) {
  json m = three_hinged_arch(1000.0);
  m["loads"].push_back({{"node", 2}, {"mz", 5.0}});
  EXPECT_NE(refusal(m).find("loads[1].mz: node 2 is a hinge: every element end there is released"), std::string::npos)
      << refusal(m);

  m = three_hinged_arch(1000.0);
  m["members"][0]["release"] = "middle";
  EXPECT_NE(refusal(m).find("members[0].release: unknown release \"middle\""), std::string::npos) << refusal(m);

  // A bar (hinged at both ends) pinned at one end, its other end free: it turns about the pin.
  // Both ends' rotations are fixed automatically (no element end turns with them), and those
  // fixed rotations hold nothing: the supports' check sees the mechanism instead of a solve
  // meeting a singular tangent.
  m = three_hinged_arch(1000.0);
  m["members"] = json::array({{{"from", 1}, {"to", 2}, {"material", "s"}, {"section", "x"}, {"release", "both"}}});
  m["supports"] = json::array({{{"node", 1}, {"type", "pinned"}}});
  m["nodes"].erase(2);
  EXPECT_NE(refusal(m).find("structure is a mechanism: the part holding node 1 and the 1 node joined to it is free to rotate"),
            std::string::npos)
      << refusal(m);

  // Contacts in the cantilever-coordinate frame: a list naming a hinged member is refused; "all"
  // leaves hinged members out (the chord frame takes them: ContactOnHinged* below).
  m = three_hinged_arch(1000.0);
  m["nodes"].push_back({{"id", 9}, {"x", 2.0}, {"y", 2.0}});
  m["supports"].push_back({{"node", 9}, {"type", "fixed"}});
  m["contacts"] = json::array({{{"node", 9}, {"members", {0}}, {"frame", "cantilever"}}});
  EXPECT_NE(refusal(m).find("contacts[0].members[0]: member 0 has a moment release or an end spring: the cantilever-coordinate"),
            std::string::npos)
      << refusal(m);
  m["contacts"] = json::array({{{"node", 9}, {"members", "all"}, {"frame", "cantilever"}}});
  EXPECT_NE(refusal(m).find("contacts[0].members: no member to touch (hinged or sprung members carry no cantilever-coordinate contact)"),
            std::string::npos)
      << refusal(m);
  m["contacts"] = json::array({{{"node", 9}, {"members", {0}}}});
  EXPECT_EQ(refusal(m), "") << refusal(m);
}

// A beam of span L clamped at both ends through rotational springs k, a load P at mid-span:
// the end rotation of the simply supported beam, PL²/16EI, less that of the end moments M,
// ML/2EI, is what the springs turn, M/k: M = (PL/8) κ/(1 + κ), κ = kL/2EI; the mid-span
// deflection PL³/48EI − ML²/8EI. A point load at a node: exact for the elements; the load is
// small (the membrane effect ~ (δ/L)² is below 1e-9).
TEST(SemiRigid, AClampedBeamOnEndSpringsCarriesTheMomentsOfSlopeDeflection) {
  const double L = 4.0, EI = 2.0, P = 1e-6;
  for (const double kappa : {0.1, 1.0, 10.0}) {
    const double k = 2.0 * EI * kappa / L;
    json m = beam_model({.L = L, .E = 1.0, .G = 0.4, .A = 1e4, .I = EI, .shear_area = 1e4, .divisions = 10});
    m["members"][0]["end_springs"] = {{"start", k}, {"end", k}};
    m["analysis"]["tolerance"] = 1e-13;  // the residual's default 1e-8 leaves ~1e-7 of the deflection
    m["supports"] = json::array({{{"node", 1}, {"type", "fixed"}}, {{"node", 2}, {"type", "fixed"}}});
    m["loads"] = json::array({{{"node", json::array({L / 2, 0.0})}, {"fy", -P}}});
    tsm::Model model;
    const RunResult r = run(m, model);
    ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
    const StepRecord& last = r.steps.back();
    const double M = P * L / 8.0 * kappa / (1.0 + kappa);
    const double deflection = P * L * L * L / (48.0 * EI) - M * L * L / (8.0 * EI);
    const int mid = model.nodes[model.elements[4].end].id;
    EXPECT_NEAR(node_displacement(model, last, mid)[1], -deflection, 1e-9 * deflection) << "κ " << kappa;
    EXPECT_NEAR(last.reactions[3 * model.node_index(1) + 2], M, 1e-9 * M) << "κ " << kappa;
    EXPECT_NEAR(last.reactions[3 * model.node_index(2) + 2], -M, 1e-9 * M) << "κ " << kappa;
    // The spring turns M/k between the clamp and the element's end: the first node off the
    // clamp turns that much plus the beam's own rotation there; the results name the springs.
    std::ostringstream text;
    tsm::io::write_results_json(text, model, r);
    EXPECT_EQ(json::parse(text.str())["elements"][0]["end_springs"]["start"], k);
  }
}

// A cantilever on a root spring k = EI/L under a tip moment M = 2πEI/L (Timoshenko elements, four
// load steps): the spring turns M/k = 2π, the beam bends into a full circle of its own: the tip
// is back on the root, turned 4π, and every node s along it turns 2π + 2πs/L.
TEST(SemiRigid, ACantileverOnARootSpringRollsUpTwiceOverItsTip) {
  const double L = 10.0, EI = 2.05e11 * 1e-2 * 1e-2 / 12.0;
  json m = beam_model({.L = L, .E = 2.05e11, .G = 7.9e10, .A = 1e-2, .I = 1e-2 * 1e-2 / 12.0,
                       .shear_area = 5.0 / 6.0 * 1e-2, .divisions = 40, .element = "timoshenko"});
  m["members"][0]["end_springs"] = {{"start", EI / L}};
  m["supports"] = json::array({{{"node", 1}, {"type", "fixed"}}});
  m["loads"] = json::array({{{"node", 2}, {"mz", 2 * std::numbers::pi * EI / L}}});
  m["analysis"]["control"]["steps"] = 4;
  m["analysis"]["tolerance"] = 1e-10;
  tsm::Model model;
  const RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  const StepRecord& last = r.steps.back();
  EXPECT_LE(node_position(model, last, 2).norm(), 1e-6 * L);
  for (int k = 1; k < model.node_count(); ++k) {
    const double s = model.nodes[k].position.x();
    EXPECT_NEAR(last.displacements[3 * k + 2], 2 * std::numbers::pi * (1.0 + s / L), 1e-7) << "node " << model.nodes[k].id;
  }
}

TEST(SemiRigid, TheReaderRefusesSpringsThatHoldNothing) {
  json m = beam_model({});
  m["supports"] = json::array({{{"node", 1}, {"type", "fixed"}}});
  m["members"][0]["end_springs"] = {{"start", 0.0}};
  EXPECT_NE(refusal(m).find("members[0].end_springs.start: a rotational spring's stiffness (moment per radian) must be a positive finite number"),
            std::string::npos)
      << refusal(m);
  m["members"][0]["end_springs"] = {{"start", 1.0}};
  m["members"][0]["release"] = "start";
  EXPECT_NE(refusal(m).find("members[0].end_springs.start: that end is released (a hinge): a spring there holds nothing"),
            std::string::npos)
      << refusal(m);
  m["members"][0].erase("release");
  m["members"][0]["end_springs"] = {{"middle", 1.0}};
  EXPECT_NE(refusal(m).find("members[0].end_springs"), std::string::npos) << refusal(m);
  m["members"][0]["end_springs"] = json::object();
  EXPECT_NE(refusal(m).find("members[0].end_springs: give start or end"), std::string::npos) << refusal(m);
  m["members"][0]["end_springs"] = {{"end", 3.0}};
  EXPECT_EQ(refusal(m), "");
}

// ---- Contacts on hinged members ----
// A Gerber beam: member AB (4 m) clamped at A, an inner hinge at B, member BC (6 m) on a roller at
// C; both members of 4 and 6 elements, the elements next to B hinged there. A rigid node drawn
// 1 mm above the beam is pushed down by 1 mm + δ (δ = 1 mm, small: linear statics holds to
// ~1e-4). A point force P on BC at a from B, b = 6 − a from C: BC is simply supported on C and
// on B, which the cantilever AB holds with its tip stiffness; B goes down (P b/6) (L³/3EI +
// L/GA_s) and the point, beyond that share of it, a²b²/(3EI·6) + ab/(6 GA_s).
double gerber_push_force(double a, double EI, double GAs, double push) {
  const double L1 = 4.0, L2 = 6.0, b = L2 - a;
  const double at_b = (b / L2) * (b / L2) * (L1 * L1 * L1 / (3.0 * EI) + (GAs > 0.0 ? L1 / GAs : 0.0));
  const double in_span = a * a * b * b / (3.0 * EI * L2) + (GAs > 0.0 ? a * b / (L2 * GAs) : 0.0);
  return push / (at_b + in_span);
}

json gerber_push(double x, double push_x, double push, bool timoshenko, int steps) {
  json m = {
      {"materials", {{"steel", {{"E", 2.0e11}, {"G", 8.0e10}}}}},
      {"sections", {{"s", {{"A", 4.0e-3}, {"I", 2.0e-5}, {"shear_area", 2.0e-3}}}}},
      {"nodes", json::array({{{"id", 1}, {"x", 0.0}, {"y", 0.0}}, {{"id", 2}, {"x", 4.0}, {"y", 0.0}},
                             {{"id", 3}, {"x", 10.0}, {"y", 0.0}}, {{"id", 9}, {"x", x}, {"y", 1e-3}}})},
      {"members", json::array({{{"from", 1}, {"to", 2}, {"divisions", 4}, {"material", "steel"}, {"section", "s"}, {"release", "end"}},
                               {{"from", 2}, {"to", 3}, {"divisions", 6}, {"material", "steel"}, {"section", "s"}, {"release", "start"}}})},
      {"supports", json::array({{{"node", 1}, {"type", "fixed"}}, {{"node", 3}, {"type", "roller-x"}},
                                {{"node", 9}, {"fix", push_x == 0.0 ? json::array({"ux", "rz"}) : json::array({"rz"})}}})},
      {"prescribed", json::array({{{"node", 9}, {"uy", -(1e-3 + push)}}})},
      {"contacts", json::array({{{"node", 9}, {"members", "all"}}})},
      {"analysis", {{"control", {{"type", "load"}, {"steps", steps}}}}},
  };
  if (push_x != 0.0) m["prescribed"][0]["ux"] = push_x;
  if (timoshenko)
    for (auto& member : m["members"]) member["element"] = "timoshenko";
  return m;
}

TEST(ContactOnHinged, APushNextToAnInnerHingeCarriesTheGerberBeamsForce) {
  const double EI = 2.0e11 * 2.0e-5, GAs = 8.0e10 * 2.0e-3, push = 1e-3;
  for (const bool timoshenko : {false, true})
    for (const double x : {4.5, 4.05, 3.7}) {  // on BC's first element (hinged at B), close to B; on AB's last
      tsm::Model model;
      const RunResult r = run(gerber_push(x, 0.0, push, timoshenko, 4), model);
      ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
      const StepRecord& last = r.steps.back();
      ASSERT_GE(last.contacts[0].element, 0);
      const double force = last.contacts[0].force;
      // On AB (x < 4) the point rides the cantilever beyond which BC hangs from B: P (x³/3EI +
      // x/GA_s) … plus what B's load adds there: solved exactly by superposition below.
      double expected;
      if (x > 4.0) {
        expected = gerber_push_force(x - 4.0, EI, timoshenko ? GAs : 0.0, push);
      } else {  // BC's only support on AB is B, unloaded: AB is a plain cantilever under P at x
        expected = push / (x * x * x / (3.0 * EI) + (timoshenko ? x / GAs : 0.0));
      }
      EXPECT_NEAR(force, expected, 2e-3 * expected) << "x " << x << (timoshenko ? " Timoshenko" : " Euler-Bernoulli");
      expect_global_equilibrium(model, last, 1e-8);
      // The hinge carries no moment: the elements ending at B report M = 0 there.
      for (size_t e = 0; e < model.elements.size(); ++e) {
        if (model.elements[e].release_end) EXPECT_EQ(last.element_forces[3 * e + 2], 0.0);
        if (model.elements[e].release_start) EXPECT_EQ(last.element_forces[3 * e + 1], 0.0);
      }
    }
}

TEST(ContactOnHinged, APointSlidesThroughAnInnerHinge) {
  // The node drawn above AB at x = 3.4 is pushed down by 1 mm + δ and along by 0.9 m in 12 steps:
  // it touches AB at x ≈ 3.85, slides over the hinge B onto BC and ends at x = 4.3, carrying there
  // what the Gerber beam's closed form gives.
  const double EI = 2.0e11 * 2.0e-5, push = 1e-3;
  tsm::Model model;
  const RunResult r = run(gerber_push(3.4, 0.9, push, false, 12), model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  const StepRecord& last = r.steps.back();
  const tsm::solver::ContactPoint& c = last.contacts[0];
  ASSERT_GE(c.element, 0);
  EXPECT_EQ(model.elements[c.element].member, 1);  // on BC now
  const double expected = gerber_push_force(0.3, EI, 0.0, push);
  EXPECT_NEAR(c.force, expected, 2e-3 * expected);
  expect_global_equilibrium(model, last, 1e-8);
  bool was_on_ab = false;
  for (const StepRecord& s : r.steps)
    if (s.converged && s.contacts[0].element >= 0 && model.elements[s.contacts[0].element].member == 0) was_on_ab = true;
  EXPECT_TRUE(was_on_ab);
}

TEST(ContactOnSprung, APushNextToARootSpringCarriesTheCantileversForce) {
  // A 4 m cantilever clamped through a root spring k = EI/L (4 elements), pushed down by δ = 1 mm
  // at x = a on its first element (the sprung one): the point goes down P a³/3EI (+ P a/GA_s),
  // and the root's turn P a/k takes it P a²/k further.
  const double EI = 2.0e11 * 2.0e-5, GAs = 8.0e10 * 2.0e-3, k = EI / 4.0, push = 1e-3;
  for (const bool timoshenko : {false, true})
    for (const double a : {0.5, 0.95}) {
      json m = gerber_push(a, 0.0, push, timoshenko, 4);
      m["nodes"] = json::array({{{"id", 1}, {"x", 0.0}, {"y", 0.0}}, {{"id", 2}, {"x", 4.0}, {"y", 0.0}}, {{"id", 9}, {"x", a}, {"y", 1e-3}}});
      m["members"] = json::array({m["members"][0]});
      m["members"][0].erase("release");
      m["members"][0]["end_springs"] = {{"start", k}};
      m["supports"] = json::array({{{"node", 1}, {"type", "fixed"}}, {{"node", 9}, {"fix", {"ux", "rz"}}}});
      tsm::Model model;
      const RunResult r = run(m, model);
      ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
      const StepRecord& last = r.steps.back();
      ASSERT_EQ(last.contacts[0].element, 0);
      const double expected = push / (a * a * a / (3.0 * EI) + (timoshenko ? a / GAs : 0.0) + a * a / k);
      EXPECT_NEAR(last.contacts[0].force, expected, 2e-3 * expected) << "a " << a << (timoshenko ? " Timoshenko" : "");
      // The spring turns by M/k: the root's moment P a, its node held.
      EXPECT_NEAR(std::abs(last.element_forces[1]), expected * a, 2e-3 * expected * a);
      expect_global_equilibrium(model, last, 1e-8);
    }
}

TEST(ContactOnHinged, AHingeAtAPinnedEndChangesNothingAtLargeDeflection) {
  // A bar pinned at both ends turns freely there, whether its end elements are hinged to the pin
  // nodes or not: a rigid node pushing it 0.3 m down at x = 0.6 m (on the end element, the
  // hinged one) gives the same path either way — the condensed contact law against the plain one
  // far from linear statics (Timoshenko elements; the bar stretches ~0.8 %).
  json m = {
      {"materials", {{"steel", {{"E", 2.0e11}, {"G", 7.7e10}}}}},
      {"sections", {{"s", {{"A", 4.0e-3}, {"I", 2.0e-5}, {"shear_area", 2.0e-3}}}}},
      {"nodes", json::array({{{"id", 1}, {"x", 0.0}, {"y", 0.0}}, {{"id", 2}, {"x", 10.0}, {"y", 0.0}}, {{"id", 9}, {"x", 0.6}, {"y", 1e-3}}})},
      {"members", json::array({{{"from", 1}, {"to", 2}, {"divisions", 10}, {"element", "timoshenko"}, {"material", "steel"},
                                {"section", "s"}}})},
      {"supports", json::array({{{"node", 1}, {"type", "pinned"}}, {{"node", 2}, {"type", "pinned"}}, {{"node", 9}, {"fix", {"ux", "rz"}}}})},
      {"prescribed", json::array({{{"node", 9}, {"uy", -0.3}}})},
      {"contacts", json::array({{{"node", 9}, {"members", "all"}}})},
      {"analysis", {{"control", {{"type", "load"}, {"steps", 6}}}, {"output", "all"}}},
  };
  tsm::Model plain_model, hinged_model;
  const RunResult plain = run(m, plain_model);
  m["members"][0]["release"] = "both";
  const RunResult hinged = run(m, hinged_model);
  ASSERT_EQ(plain.status, tsm::solver::Status::converged) << plain.message;
  ASSERT_EQ(hinged.status, tsm::solver::Status::converged) << hinged.message;
  ASSERT_EQ(plain.steps.size(), hinged.steps.size());
  for (size_t k = 0; k < plain.steps.size(); ++k) {
    const auto &a = plain.steps[k].contacts[0], &b = hinged.steps[k].contacts[0];
    EXPECT_EQ(a.element, b.element) << "step " << k + 1;
    EXPECT_NEAR(a.force, b.force, 1e-7 * std::abs(a.force) + 1e-6) << "step " << k + 1;
    EXPECT_NEAR(a.alpha, b.alpha, 1e-9) << "step " << k + 1;
  }
  EXPECT_EQ(plain.steps.back().contacts[0].element, 0);  // still on the end element
  EXPECT_GT(plain.steps.back().contacts[0].force, 1e5);
}

}  // namespace

namespace {

/// A portal (columns 3 m, beam 4 m, 2 elements each) on two pins with its beam released at both
/// ends: four hinges, a sway mechanism. `control`: the analysis' control.
json four_hinged_portal(const json& control) {
  return {{"materials", {{"steel", {{"E", 2.1e11}}}}},
          {"sections", {{"s", {{"A", 5e-3}, {"I", 8e-5}}}}},
          {"nodes", json::array({{{"id", 1}, {"x", 0}, {"y", 0}}, {{"id", 2}, {"x", 0}, {"y", 3}},
                                 {{"id", 3}, {"x", 4}, {"y", 3}}, {{"id", 4}, {"x", 4}, {"y", 0}}})},
          {"members", json::array({{{"from", 1}, {"to", 2}, {"material", "steel"}, {"section", "s"}, {"divisions", 2}},
                                   {{"from", 2}, {"to", 3}, {"material", "steel"}, {"section", "s"}, {"divisions", 2},
                                    {"release", "both"}},
                                   {{"from", 3}, {"to", 4}, {"material", "steel"}, {"section", "s"}, {"divisions", 2}}})},
          {"supports", json::array({{{"node", 1}, {"type", "pinned"}}, {{"node", 4}, {"type", "pinned"}}})},
          {"loads", json::array({{{"node", 2}, {"fx", 1000.0}}})},
          {"analysis", {{"control", control}}}};
}

}  // namespace

// A mechanism among hinges, which the supports' check (connected parts as rigid bodies) cannot
// see: the unloaded tangent is singular along the motion no element resists. It is named — the
// nodes that move most and which way — and no step is cut back for it (a smaller step meets it
// too); under displacement control alike (it "converged" at λ = 1e-27 once).
TEST(Hinges, AFourHingedPortalIsNamedAsTheMechanismItIs) {
  for (const json& control : {json{{"type", "load"}, {"steps", 2}},
                              json{{"type", "displacement"}, {"node", 2}, {"dof", "ux"}, {"target", 0.1}, {"steps", 2}}}) {
    tsm::Model model;
    const RunResult r = run(four_hinged_portal(control), model);
    ASSERT_EQ(r.status, tsm::solver::Status::singular) << r.message;
    const tsm::solver::StepFailure& f = r.failure.step_failure;
    ASSERT_EQ(f.reason, tsm::solver::StepFailure::Reason::mechanism) << r.message;
    EXPECT_EQ(r.failure.cutbacks, 0);
    // The sway: the beam (nodes 2, 3 and its middle node) moves along x as a rigid body; the
    // columns turn about their pins, their middle nodes moving half as much.
    EXPECT_EQ(f.moving_count, 3);
    EXPECT_NEAR(std::abs(f.moving_direction.x()), 1.0, 1e-9);
    EXPECT_NEAR(f.moving_direction.y(), 0.0, 1e-6);
    EXPECT_NE(r.message.find("the structure is a mechanism: unloaded, it can move with no element deforming — nodes 2, 3 "
                             "and "),
              std::string::npos)
        << r.message;
    EXPECT_NE(r.message.find("moving along x"), std::string::npos) << r.message;
    EXPECT_TRUE(r.steps.empty() || !r.steps.back().converged);
  }
}

TEST(Hinges, AFinerFourHingedPortalWhoseTangentFactorisesIsNamedToo) {
  // Eight elements a member (examples/portal-frame.json's mesh with pinned feet and a hinged beam):
  // the unloaded tangent's sway pivot rounds off zero and the factorisation goes through, the first
  // correction blows up — and that failure from the unloaded state is named as the mechanism it is,
  // as up front (unloaded_mechanism, what `tsmframe plot` tells), its smallest eigenvalue at
  // round-off level (below 1e-3 of the 1e-9 shift).
  json m = four_hinged_portal({{"type", "load"}, {"steps", 2}});
  for (json& member : m["members"]) member["divisions"] = 8;
  tsm::Model model;
  const RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::singular) << r.message;
  EXPECT_EQ(r.failure.step_failure.reason, tsm::solver::StepFailure::Reason::mechanism) << r.message;
  EXPECT_EQ(r.failure.cutbacks, 0);
  EXPECT_NE(r.message.find("moving along x"), std::string::npos) << r.message;
  const std::optional<std::string> up_front = tsm::solver::unloaded_mechanism(model);
  ASSERT_TRUE(up_front.has_value());
  EXPECT_EQ(up_front->rfind("the structure is a mechanism: unloaded, it can move with no element deforming — nodes 2, 3", 0), 0u)
      << *up_front;
}

TEST(Hinges, ASlenderButSoundStructureIsNoMechanism) {
  // A cantilever 1,000 times longer than the radius of gyration in 100 elements: its lowest mode's
  // stiffness is ~1.5e-8 of the largest diagonal entry — within the hundred shifts a tangent that did
  // not factorise is granted, far above round-off: no mechanism.
  const json m = {{"materials", {{"steel", {{"E", 2e11}}}}},
                  {"sections", {{"s", {{"A", 1e-2}, {"I", 1e-8}}}}},
                  {"nodes", json::array({{{"id", 1}, {"x", 0}, {"y", 0}}, {{"id", 2}, {"x", 1}, {"y", 0}}})},
                  {"members", json::array({{{"from", 1}, {"to", 2}, {"material", "steel"}, {"section", "s"}, {"divisions", 100}}})},
                  {"supports", json::array({{{"node", 1}, {"type", "fixed"}}})},
                  {"loads", json::array({{{"node", 2}, {"fy", -1.0}}})}};
  EXPECT_FALSE(tsm::solver::unloaded_mechanism(tsm::io::read_model(m)).has_value());
  EXPECT_TRUE(tsm::solver::unloaded_mechanism(tsm::io::read_model(four_hinged_portal({{"type", "load"}}))).has_value());
}

TEST(Hinges, ThreeHingesInALineLetTheMiddleOneDrop) {
  // Two bars pinned at their outer ends and hinged together at the middle, in a straight line:
  // the middle hinge may move across the line (to first order) with nothing deforming.
  json m = four_hinged_portal({{"type", "load"}, {"steps", 1}});
  m["nodes"] = json::array({{{"id", 1}, {"x", 0}, {"y", 0}}, {{"id", 2}, {"x", 2}, {"y", 0}}, {{"id", 3}, {"x", 4}, {"y", 0}}});
  m["members"] = json::array({{{"from", 1}, {"to", 2}, {"material", "steel"}, {"section", "s"}, {"divisions", 3}, {"release", "end"}},
                              {{"from", 2}, {"to", 3}, {"material", "steel"}, {"section", "s"}, {"divisions", 3}}});
  m["supports"] = json::array({{{"node", 1}, {"type", "pinned"}}, {{"node", 3}, {"type", "pinned"}}});
  m["loads"] = json::array({{{"node", 2}, {"fy", -1000.0}}});
  tsm::Model model;
  const RunResult r = run(m, model);
  const tsm::solver::StepFailure& f = r.failure.step_failure;
  ASSERT_EQ(f.reason, tsm::solver::StepFailure::Reason::mechanism) << r.message;
  EXPECT_EQ(f.moving_count, 1);
  ASSERT_EQ(f.moving_nodes.size(), 1u);
  EXPECT_EQ(model.nodes[f.moving_nodes[0]].id, 2);
  EXPECT_NEAR(std::abs(f.moving_direction.y()), 1.0, 1e-9);
  EXPECT_NE(r.message.find("node 2 moving along y"), std::string::npos) << r.message;
}
