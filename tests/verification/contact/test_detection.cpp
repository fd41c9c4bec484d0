// Detection end to end: contacts closing together and settling, a dof reached only through an
// open contact, a node crossing the beam, sliding over many elements, across a joint, into a
// column, up an L-frame, or off a free end within one step, two nodes on one element, a node
// just outside an arch, two contacts at once, beam on beam, a beam tip dragged along a beam.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include <Eigen/Dense>

#include "support/contact_models.hpp"

namespace {

using namespace tsm::test;
using tsm::solver::RunResult;
using tsm::solver::StepRecord;

/// The contacts in touch at a step, each checked to push.
int pushing_contacts(const tsm::solver::StepRecord& step) {
  int touching = 0;
  for (const tsm::solver::ContactPoint& c : step.contacts)
    if (c.element >= 0) {
      ++touching;
      EXPECT_GT(c.force, 0.0);
    }
  return touching;
}

TEST(ContactDetection, ManyContactsClosingTogetherSettleInOneLookAheadAndAFailureSaysHow) {
  // The two beams loaded in one step to the first contacts: the predictor closes 85 contacts,
  // of which one is right. Released a few per converged iterate (the outermost pulling ones),
  // the set settled in 75 iterations, beyond the default 50; the look-ahead on the tangent
  // releases the other 84 together: 9 iterations. With too few iterations the step fails, and
  // its message names the way out.
  json m = pressed_beams(-20000.0 / 10240.0, 1);
  m["analysis"]["cutback"] = false;
  tsm::Model model;
  const RunResult settled = run(m, model);
  ASSERT_EQ(settled.status, tsm::solver::Status::converged) << settled.message;
  EXPECT_LE(settled.steps.back().iterations, 12);
  const int touching = pushing_contacts(settled.steps.back());
  EXPECT_GE(touching, 1);
  EXPECT_LE(touching, 5);
  expect_equilibrium(model, settled.steps.back());
  m["analysis"]["max_iterations"] = 5;
  const RunResult failed = run(m, model);
  ASSERT_EQ(failed.status, tsm::solver::Status::max_iterations) << failed.message;
  EXPECT_NE(failed.message.find("so the set of contacts in touch did not settle (with 201 contact nodes it may settle "
                                "given more: analysis.max_iterations, now 5, or smaller steps)"),
            std::string::npos)
      << failed.message;
}

TEST(ContactDetection, SevenHundredContactsAlongTheBentBeamsNormalSettleAsAlongTheChords) {
  // 701 contact nodes pressed in 10 steps, the force along the bent beam's normal (the default):
  // the release look-ahead forecast on the bent tangent released only the two pulling contacts
  // at the over-held zone's edges per converged iterate (its normal's turning, a term of the
  // contact's own stiffness times Y, was left behind in K), and the first step failed after 8
  // cutbacks; forecast along the chords' normals the zone lets go at once, as with the chord's
  // normal (24 steps there too).
  tsm::Model model;
  const RunResult r = run(pressed_beams(-2000.0, 10, 2100, 700), model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  EXPECT_LE(r.steps.size(), 30u);
  EXPECT_GT(pushing_contacts(r.steps.back()), 300);
  expect_equilibrium(model, r.steps.back());
}

TEST(ContactDetection, DisplacementControlOfADofReachedOnlyThroughAnOpenContactFailsAtOnceSayingSo) {
  // The two beams, the lower beam's mid-span uy controlled: the load on the upper beam reaches it
  // only once the contacts close, so at the start the dof does not move under the load. Ten
  // cutbacks could not change that (the tangent at the step's start is the same); the run now
  // stops at once, "singular", and says what to control instead.
  json m = pressed_beams(-2000.0, 10);
  m["analysis"]["control"] = {{"type", "displacement"}, {"node", {5.0, 0.0}}, {"dof", "uy"}, {"target", -0.05}, {"steps", 10}};
  tsm::Model model;
  const RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::singular) << r.message;
  ASSERT_EQ(r.steps.size(), 1u);
  EXPECT_EQ(r.steps[0].cutbacks, 0);
  EXPECT_NE(r.message.find("the controlled dof does not move under the load (if the load reaches it only through a "
                           "contact still open, it does not until that closes"),
            std::string::npos)
      << r.message;
}

TEST(ContactDetection, APusherThatSlidesOffAFreeEndIsNoted) {
  // A rigid pusher 5 mm under a 2 m cantilever (10 elements) moves 1.5 m along it and 3 cm up in
  // 31 steps: it lifts the beam, slides along it across element ends and off its free end, and
  // lets go there. (Found as two overlapping cantilevers under load control, one step jumping past
  // the maximum to the upper tip hanging past the lower beam's end, silently.)
  json m = {{"materials", {{"steel", {{"E", 2e11}, {"nu", 0.3}}}}},
            {"sections", {{"s", {{"A", 1e-3}, {"I", 1e-6}}}}},
            {"nodes", json::array({{{"id", 1}, {"x", 0.0}, {"y", 0.0}}, {{"id", 2}, {"x", 2.0}, {"y", 0.0}},
                                   {{"id", 9}, {"x", 1.0}, {"y", -0.005}}})},
            {"members", json::array({{{"from", 1}, {"to", 2}, {"divisions", 10}, {"material", "steel"}, {"section", "s"}}})},
            {"supports", json::array({{{"node", 1}, {"type", "fixed"}}, {{"node", 9}, {"fix", {"rz"}}}})},
            {"prescribed", json::array({{{"node", 9}, {"ux", 1.5}, {"uy", 0.03}}})},
            {"contacts", json::array({{{"node", 9}, {"members", {0}}}})},
            {"analysis", {{"control", {{"type", "load"}, {"steps", 31}}}}}};
  tsm::Model model;
  const RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  int let_go = -1;
  for (const StepRecord& s : r.steps)
    if (s.converged && let_go < 0 && !s.slid_off.empty()) let_go = s.step;
  ASSERT_GT(let_go, 1);
  EXPECT_EQ(r.steps[let_go - 2].contacts.at(0).element, 9) << "on the last element the step before";
  EXPECT_LT(r.steps[let_go - 1].contacts.at(0).element, 0);
  std::string said;
  for (const std::string& note : r.notes)
    if (note.find("slid off") != std::string::npos) said = note;
  EXPECT_EQ(said, "the contact of node 9 slid off the free end of member 0 (past element 10's end) and let go in step " +
                      std::to_string(let_go));
}

// ---- A node crossing the beam within one step; two contacts; beam on beam ----

TEST(ContactDetection, ANodeCrossingTheBeamInOneStepGivesTheSameAnswerAsManySteps) {
  BeamSpec b;
  b.divisions = 20;
  b.A = 1e6;
  tsm::Model one, many;
  // Both runs converge tightly (relative residual 1e-12), so they must agree to 1e-9.
  json m1 = pusher_model(b, 0.55, -0.01, 0.0, 0.06, 1), m10 = pusher_model(b, 0.55, -0.01, 0.0, 0.06, 10);
  m1["analysis"]["tolerance"] = m10["analysis"]["tolerance"] = 1e-12;
  const RunResult a = run(m1, one);
  const RunResult c = run(m10, many);
  ASSERT_EQ(a.status, tsm::solver::Status::converged) << a.message;
  ASSERT_EQ(c.status, tsm::solver::Status::converged) << c.message;
  const auto& p = contact_of(a.steps.back());
  const auto& q = contact_of(c.steps.back());
  EXPECT_EQ(p.element, q.element);
  EXPECT_NEAR(p.alpha, q.alpha, 1e-9);
  EXPECT_NEAR(p.force, q.force, 1e-9 * q.force);
}

// ---- Many posts pressing one beam: the active set ----
// A 20 m beam, pinned at its ends, pushed up by 40 rigid posts to 0.05, 0.10, 0.15 m in turn.
// The tall posts near the ends lever the beam up and the others lose contact. Releasing every
// post that pulls at once lets some of them through the beam further on; such a post must take
// part again (before, the step failed at every cutback). Checked: every post is either in
// contact and pressing, or below the beam's deflected centre line (EB elements: the Hermite
// cubic of each element in its chord frame).

TEST(ContactDetection, ManyPostsFindTheirActiveSetWithoutPassingThroughTheBeam) {
  const int posts = 40, divisions = 40;
  const double L = 20.0;
  json m = {
      {"materials", {{"steel", {{"E", 2.05e11}}}}},
      {"sections", {{"box", {{"A", 1e-2}, {"I", 1e-4}}}}},
      {"nodes", json::array({{{"id", 1}, {"x", 0.0}, {"y", 0.0}}, {{"id", 2}, {"x", L}, {"y", 0.0}}})},
      {"members", json::array({{{"from", 1}, {"to", 2}, {"divisions", divisions}, {"material", "steel"}, {"section", "box"}}})},
      {"supports", json::array({{{"node", 1}, {"type", "pinned"}}, {{"node", 2}, {"fix", {"uy"}}}})},
      {"prescribed", json::array()},
      {"contacts", json::array()},
      {"analysis", {{"control", {{"type", "load"}, {"steps", 10}}}, {"output", "last"}}},
  };
  for (int k = 0; k < posts; ++k) {
    const int id = 100 + k;
    m["nodes"].push_back({{"id", id}, {"x", 0.3 + k * 19.4 / (posts - 1) + 0.013}, {"y", 0.0}});
    m["supports"].push_back({{"node", id}, {"fix", {"ux", "rz"}}});
    m["prescribed"].push_back({{"node", id}, {"uy", 0.05 * (1 + k % 3)}});
    m["contacts"].push_back({{"node", id}, {"members", "all"}});
  }
  tsm::Model model;
  const RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  const StepRecord& last = r.steps.back();
  ASSERT_EQ(last.load_factor, 1.0);
  int pressing = 0;
  for (int k = 0; k < posts; ++k) {
    const tsm::solver::ContactPoint& c = contact_of(last, k);
    if (c.element >= 0) {
      ++pressing;
      EXPECT_GE(c.force, 0.0) << "post " << k;
      continue;
    }
    // A released post: find the element below it and its deflected centre line there.
    const Eigen::Vector2d post = node_position(model, last, 100 + k);
    bool found = false;
    for (const tsm::Element& e : model.elements) {
      const Eigen::Vector2d a = model.nodes[e.start].position + last.displacements.segment<2>(3 * e.start);
      const Eigen::Vector2d b = model.nodes[e.end].position + last.displacements.segment<2>(3 * e.end);
      const Eigen::Vector2d t = (b - a).normalized(), n(-t.y(), t.x());
      const double l = (b - a).norm(), xi = (post - a).dot(t) / l;
      if (xi < 0.0 || xi > 1.0) continue;
      const double beta = std::atan2(b.y() - a.y(), b.x() - a.x()) - std::atan2(model.nodes[e.end].position.y() - model.nodes[e.start].position.y(),
                                                                               model.nodes[e.end].position.x() - model.nodes[e.start].position.x());
      const double ti = last.displacements[3 * e.start + 2] - beta, tj = last.displacements[3 * e.end + 2] - beta;
      const double w = l * (ti * (xi - 2 * xi * xi + xi * xi * xi) + tj * (xi * xi * xi - xi * xi));
      EXPECT_LE((post - a).dot(n), w + 1e-9 * L) << "post " << k << " is through the beam";
      found = true;
      break;
    }
    EXPECT_TRUE(found) << "post " << k << " beyond the beam";
  }
  EXPECT_GE(pressing, 2);
  EXPECT_LT(pressing, posts);  // most posts have let go
}

TEST(ContactDetection, ANodeSlidingOverManyElementsInOneStepStillTouches) {
  // A wheel rolls 10 m along a 20 m simply supported rail of 1,000 elements, pressing 5 cm into
  // it: 25 elements a step, far beyond the one element's reach around the node where its side is
  // read directly. It must touch in the first step and press on to the end (the sides are carried
  // along the member), with the force of the linear point-load formula,
  // δ = P (a²b²/(3EIL) + ab/(G A_s L)).
  BeamSpec b{.L = 20.0, .E = 2.1e11, .G = 8.1e10, .A = 7.7e-3, .I = 3e-5, .shear_area = 3.5e-3, .divisions = 1000,
             .element = "timoshenko"};
  json m = beam_model(b);
  m["nodes"].push_back({{"id", 9}, {"x", 5.0}, {"y", 0.001}});
  m["supports"] = json::array({{{"node", 1}, {"type", "pinned"}}, {{"node", 2}, {"type", "roller-x"}},
                               {{"node", 9}, {"fix", json::array({"rz"})}}});
  m["prescribed"] = json::array({{{"node", 9}, {"ux", 10.0}, {"uy", -0.051}}});
  m["contacts"] = json::array({{{"node", 9}, {"members", "all"}}});
  m["analysis"] = {{"control", {{"type", "load"}, {"steps", 20}}}};
  tsm::Model model;
  const RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  double largest = 0.0;
  for (const StepRecord& s : r.steps) {
    const tsm::solver::ContactPoint& c = contact_of(s);
    ASSERT_GE(c.element, 0) << "step " << s.step << ": the wheel went through the rail";
    const double a = 5.0 + 10.0 * s.load_factor, bb = 20.0 - a, depth = 0.051 * s.load_factor - 0.001;
    const double compliance = a * a * bb * bb / (3.0 * 2.1e11 * 3e-5 * 20.0) + a * bb / (8.1e10 * 3.5e-3 * 20.0);
    largest = std::max(largest, std::abs(c.force * compliance / depth - 1.0));
    EXPECT_NEAR(c.force, depth / compliance, 0.005 * depth / compliance) << "step " << s.step;
    EXPECT_NEAR(contact_arc_length(c, 20.0, 1000), a, 1e-3) << "step " << s.step;
  }
  std::printf("[figure] wheel on a 1000-element rail: force within %.2e of the linear formula\n", largest);
}

TEST(ContactDetection, ANodeDraggedAcrossAMemberJointInOneStepStillTouches) {
  // The same kind of pass in a beam built of two members meeting end to end (the second drawn
  // either way): a pusher dragged from 3.03 m to 7.03 m over a 10 m pinned beam, 0.3 m down, in
  // ONE step, ends 2 m past the joint at 5 m. The side it came from is carried across the joint
  // (two members meeting there and nothing else); before, it went through the beam without
  // touching. The answer is that of the same mesh drawn as one member, to round-off. With a
  // column under the joint in the contact's set (a T: the beam's top side goes on into the next
  // span's top, past the column; the pusher's side is also read off the column beyond its top,
  // left of its line, which is no side of the beam) it is that of the contact on the beam's two
  // members only, and of the same drag in 10 steps.
  const auto model_of = [](int members, bool reversed) {
    json m = {{"materials", {{"steel", {{"E", 2e11}, {"G", 7.7e10}}}}},
              {"sections", {{"s", {{"A", 0.004}, {"I", 2e-5}, {"shear_area", 0.002}}}}},
              {"nodes", json::array({{{"id", 1}, {"x", 0.0}, {"y", 0.0}}, {{"id", 2}, {"x", 5.0}, {"y", 0.0}},
                                     {{"id", 3}, {"x", 10.0}, {"y", 0.0}}, {{"id", 9}, {"x", 3.03}, {"y", 0.001}}})},
              {"supports", json::array({{{"node", 1}, {"type", "pinned"}}, {{"node", 3}, {"type", "pinned"}}})},
              {"prescribed", json::array({{{"node", 9}, {"ux", 4.0}, {"uy", -0.3}}})},
              {"contacts", json::array({{{"node", 9}, {"members", "all"}}})},
              {"analysis", {{"control", {{"type", "load"}, {"steps", 1}}}}}};
    const auto member = [](int from, int to, int divisions) {
      return json{{"from", from}, {"to", to}, {"divisions", divisions}, {"element", "timoshenko"},
                  {"material", "steel"}, {"section", "s"}};
    };
    m["members"] = members == 1 ? json::array({member(1, 3, 20)})
                                : json::array({member(1, 2, 10), reversed ? member(3, 2, 10) : member(2, 3, 10)});
    if (members == 1) m["nodes"].erase(1);
    if (members == 3) {  // a column from (5, −4) up to the joint, clamped at its foot
      m["nodes"].push_back({{"id", 4}, {"x", 5.0}, {"y", -4.0}});
      m["members"].push_back(member(4, 2, 8));
      m["supports"].push_back({{"node", 4}, {"type", "fixed"}});
    }
    return m;
  };
  tsm::Model one_model;
  const RunResult one = run(model_of(1, false), one_model);
  ASSERT_EQ(one.status, tsm::solver::Status::converged) << one.message;
  const double force = contact_of(one.steps.back()).force;
  ASSERT_GT(force, 4e5);
  for (const bool reversed : {false, true}) {
    tsm::Model model;
    const RunResult r = run(model_of(2, reversed), model);
    ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
    const tsm::solver::ContactPoint& c = contact_of(r.steps.back());
    ASSERT_GE(c.element, 0) << "the pusher went through the beam (reversed: " << reversed << ")";
    EXPECT_EQ(model.elements[c.element].member, 1);
    EXPECT_NEAR(c.force, force, 1e-8 * force) << "reversed: " << reversed;
    const int pusher = model.node_index(9), one_pusher = one_model.node_index(9);
    EXPECT_NEAR(r.steps.back().reactions[3 * pusher], one.steps.back().reactions[3 * one_pusher], 1e-8 * force);
  }
  json beam_only = model_of(3, false);
  beam_only["contacts"][0]["members"] = {0, 1};
  tsm::Model beam_model_;
  const RunResult on_beam = run(beam_only, beam_model_);
  ASSERT_EQ(on_beam.status, tsm::solver::Status::converged) << on_beam.message;
  const double supported = contact_of(on_beam.steps.back()).force;
  ASSERT_GT(supported, 2e5);
  for (const int steps : {1, 10}) {
    json tee = model_of(3, false);
    tee["analysis"]["control"]["steps"] = steps;
    tsm::Model model;
    const RunResult r = run(tee, model);
    ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
    const tsm::solver::ContactPoint& c = contact_of(r.steps.back());
    ASSERT_GE(c.element, 0) << "the pusher went through the beam (T joint, " << steps << " steps)";
    EXPECT_EQ(model.elements[c.element].member, 1);
    EXPECT_NEAR(c.force, supported, 1e-8 * supported) << steps << " steps";
  }
}

TEST(ContactDetection, ANodeDraggedIntoAColumnInOneStepStopsAtIt) {
  // A pusher pressed onto a pinned beam's top at x = 3 m and dragged 2.02 m right, 1 cm down, in
  // ONE step, towards a cross joint at 5 m (columns 2 m up and down, pinned at their ends, all in
  // the contact's set): the column standing up is in its way. The iterate puts the pusher 2 cm
  // past the joint, beyond the span of every element whose side it knows (the far span's top is
  // rightly not connected to the near span's across the column), so no element it ends within had
  // it cross: before, it went through beam and column without touching anything. Its path from
  // the converged state crosses the near span's top: contact starts there and is handed along the
  // beam into the corner, where the column's left face stops it — as in 10 steps.
  json m = {{"materials", {{"steel", {{"E", 2e11}, {"G", 7.7e10}}}}},
            {"sections", {{"s", {{"A", 0.004}, {"I", 2e-5}, {"shear_area", 0.002}}}}},
            {"nodes", json::array({{{"id", 1}, {"x", 0.0}, {"y", 0.0}}, {{"id", 2}, {"x", 10.0}, {"y", 0.0}},
                                   {{"id", 3}, {"x", 5.0}, {"y", 0.0}}, {{"id", 4}, {"x", 5.0}, {"y", 2.0}},
                                   {{"id", 5}, {"x", 5.0}, {"y", -2.0}}, {{"id", 9}, {"x", 3.0}, {"y", 0.001}}})},
            {"supports", json::array({{{"node", 1}, {"type", "pinned"}}, {{"node", 2}, {"type", "pinned"}},
                                      {{"node", 4}, {"type", "pinned"}}, {{"node", 5}, {"type", "pinned"}}})},
            {"prescribed", json::array({{{"node", 9}, {"ux", 2.02}, {"uy", -0.01}}})},
            {"contacts", json::array({{{"node", 9}, {"members", "all"}}})},
            {"analysis", {{"control", {{"type", "load"}, {"steps", 1}}}}}};
  const auto member = [](int from, int to, int divisions) {
    return json{{"from", from}, {"to", to}, {"divisions", divisions}, {"element", "timoshenko"}, {"material", "steel"}, {"section", "s"}};
  };
  m["members"] = json::array({member(1, 3, 10), member(3, 2, 10), member(3, 4, 4), member(3, 5, 4)});
  // Along the bent beams' normals too: in the corner the pusher rests on the joint, a vertex,
  // which pushes along both chords' normals (vertex.hpp); along the bent ones its force ran away.
  for (const char* normal : {"chord", "deflected"}) {
    for (const int steps : {1, 10}) {
      m["contacts"][0]["normal"] = normal;
      m["analysis"]["control"]["steps"] = steps;
      tsm::Model model;
      const RunResult r = run(m, model);
      ASSERT_EQ(r.status, tsm::solver::Status::converged) << normal << ", " << steps << " steps: " << r.message;
      const tsm::solver::ContactPoint& c = contact_of(r.steps.back());
      ASSERT_GE(c.element, 0) << "the pusher went through beam and column (" << steps << " steps)";
      // At the joint: on the near span's last element or the upper column's first, or on both.
      const int joint = model.node_index(3);
      for (const int e : {c.element, c.partner}) {
        if (e < 0) continue;
        const tsm::Element& element = model.elements[e];
        EXPECT_TRUE(element.member == 0 || element.member == 2) << steps << " steps: member " << element.member;
        EXPECT_TRUE(element.start == joint || element.end == joint) << steps << " steps: element " << e << " is not at the joint";
      }
      EXPECT_GT(c.force, 1e6) << steps << " steps: the column is pushed 2 cm at its foot";
    }
  }
}

TEST(ContactDetection, TwoNodesPressingOneElementBothTouchIt) {
  // Two pushers 0.4 m apart over one 2.5 m element of a pinned beam, both pushed 10 cm down.
  // Once the tracker refused a second node on a taken element (and before that let it through
  // the beam); the element now carries both points (issue 27) and the coarse mesh gives the fine
  // mesh's answer: pushed at 2.6 m the beam sags more at 3.0 m than 10 cm, so only node 9
  // touches, with the fine mesh's force, and node 8 ends above the beam.
  json m = {{"materials", {{"steel", {{"E", 2e11}, {"G", 7.7e10}}}}},
            {"sections", {{"s", {{"A", 0.004}, {"I", 2e-5}, {"shear_area", 0.002}}}}},
            {"nodes", json::array({{{"id", 1}, {"x", 0.0}, {"y", 0.0}}, {{"id", 2}, {"x", 10.0}, {"y", 0.0}},
                                   {{"id", 8}, {"x", 3.0}, {"y", 0.001}}, {{"id", 9}, {"x", 2.6}, {"y", 0.001}}})},
            {"members", json::array({{{"from", 1}, {"to", 2}, {"divisions", 4}, {"element", "timoshenko"},
                                      {"material", "steel"}, {"section", "s"}}})},
            {"supports", json::array({{{"node", 1}, {"type", "pinned"}}, {{"node", 2}, {"type", "roller-x"}},
                                      {{"node", 8}, {"fix", {"ux"}}}, {{"node", 9}, {"fix", {"ux"}}}})},
            {"prescribed", json::array({{{"node", 8}, {"uy", -0.1}}, {{"node", 9}, {"uy", -0.1}}})},
            {"contacts", json::array({{{"node", 8}, {"members", "all"}}, {{"node", 9}, {"members", "all"}}})},
            {"analysis", {{"control", {{"type", "load"}, {"steps", 5}}}}}};
  tsm::Model model;
  const RunResult coarse = run(m, model);
  ASSERT_EQ(coarse.status, tsm::solver::Status::converged) << coarse.message;
  m["members"][0]["divisions"] = 40;
  const RunResult fine = run(m, model);
  ASSERT_EQ(fine.status, tsm::solver::Status::converged) << fine.message;
  for (const RunResult* r : {&coarse, &fine}) {
    EXPECT_LT(contact_of(r->steps.back(), 0).element, 0);
    EXPECT_GE(contact_of(r->steps.back(), 1).element, 0);
  }
  const double force = contact_of(fine.steps.back(), 1).force;
  EXPECT_GT(force, 1e4);
  // The force acts along the chord's normal (the paper's): on the 2.5 m element that is ~0.01 rad
  // off the beam's own at the point, which leaves 3·10⁻⁴ (issue 27, part 2).
  EXPECT_NEAR(contact_of(coarse.steps.back(), 1).force, force, 1e-3 * force);
  const int under_8 = beam_node_at(model, 3.0);
  ASSERT_GE(under_8, 0);
  EXPECT_LT(node_displacement(model, fine.steps.back(), model.nodes[under_8].id)[1], -0.1);
}

TEST(ContactDetection, ANodeJustOutsideAnArchReadsItsSideOffTheElementUnderIt) {
  // A clamped half-circle arch (radius 5 m, 40 elements) and a pusher starting 0.1 mm outside it,
  // inside the sagitta of the chords (3.9 mm): just past an element's end the next chord's line
  // extended runs outside the arch, so reading the side off it said "inside", and carried round
  // the arch that side let the pusher, moved to 1 cm inside the crown in one step, go through
  // without touching. Sides are now read only off elements that hold the node, or whose
  // neighbour past that end does not; the pusher then ends as the same push made at the crown.
  const auto arch = [](double angle_from, double angle_to) {
    const double pi = std::numbers::pi, a0 = angle_from * pi / 180.0, a1 = angle_to * pi / 180.0;
    const double x0 = 5.0001 * std::cos(a0), y0 = 5.0001 * std::sin(a0), x1 = 4.99 * std::cos(a1), y1 = 4.99 * std::sin(a1);
    return json{{"materials", {{"steel", {{"E", 2e11}, {"G", 7.7e10}}}}},
                {"sections", {{"s", {{"A", 0.004}, {"I", 2e-5}, {"shear_area", 0.002}}}}},
                {"nodes", json::array({{{"id", 1}, {"x", -5.0}, {"y", 0.0}}, {{"id", 2}, {"x", 5.0}, {"y", 0.0}},
                                       {{"id", 9}, {"x", x0}, {"y", y0}}})},
                {"members", json::array({{{"from", 1}, {"to", 2}, {"divisions", 40}, {"element", "timoshenko"}, {"material", "steel"},
                                          {"section", "s"}, {"arc", {{"center", {0.0, 0.0}}, {"sweep", -pi}}}}})},
                {"supports", json::array({{{"node", 1}, {"type", "fixed"}}, {{"node", 2}, {"type", "fixed"}},
                                          {{"node", 9}, {"fix", json::array({"rz"})}}})},
                {"prescribed", json::array({{{"node", 9}, {"ux", x1 - x0}, {"uy", y1 - y0}}})},
                {"contacts", json::array({{{"node", 9}, {"members", "all"}}})},
                {"analysis", {{"control", {{"type", "load"}, {"steps", 1}}}}}};
  };
  tsm::Model pushed_model, slid_model;
  const RunResult pushed = run(arch(91.0, 91.0), pushed_model);
  ASSERT_EQ(pushed.status, tsm::solver::Status::converged) << pushed.message;
  const tsm::solver::ContactPoint& there = contact_of(pushed.steps.back());
  ASSERT_GT(there.force, 1e4);
  const RunResult slid = run(arch(126.87, 91.0), slid_model);
  ASSERT_EQ(slid.status, tsm::solver::Status::converged) << slid.message;
  const tsm::solver::ContactPoint& c = contact_of(slid.steps.back());
  ASSERT_GE(c.element, 0) << "the pusher went through the arch";
  EXPECT_EQ(c.element, there.element);
  EXPECT_NEAR(c.force, there.force, 1e-9 * there.force);
}

TEST(ContactDetection, APusherSlidingUpAnLFramesOuterFaceLeavesAtTheCorner) {
  // An L-frame (column (0,0)–(0,4) clamped, beam (0,4)–(4,4) pinned at its end, all members in
  // the contact's set) and a rigid pusher on the column's outer face, moved up 2 m and 5 cm
  // into it in 20 steps. It presses the column, is handed across the corner to the beam's top
  // (the same, outer, side) and, once above the beam's line, lets go: the frame springs back
  // unstressed. Before, it went on pressing the beam's start from inside the corner
  // (200 MN) until it failed with "contact points keep hopping".
  const auto member = [](int from, int to) {
    return json{{"from", from}, {"to", to}, {"divisions", 8}, {"element", "timoshenko"}, {"material", "steel"}, {"section", "s"}};
  };
  json m = {{"materials", {{"steel", {{"E", 2e11}, {"G", 7.7e10}}}}},
            {"sections", {{"s", {{"A", 0.01}, {"I", 1e-4}, {"shear_area", 0.005}}}}},
            {"nodes", json::array({{{"id", 1}, {"x", 0.0}, {"y", 0.0}}, {{"id", 2}, {"x", 0.0}, {"y", 4.0}},
                                   {{"id", 3}, {"x", 4.0}, {"y", 4.0}}, {{"id", 9}, {"x", -0.001}, {"y", 3.0}}})},
            {"members", json::array({member(1, 2), member(2, 3)})},
            {"supports", json::array({{{"node", 1}, {"type", "fixed"}}, {{"node", 3}, {"type", "pinned"}}})},
            {"prescribed", json::array({{{"node", 9}, {"ux", 0.05}, {"uy", 2.0}}})},
            {"contacts", json::array({{{"node", 9}, {"members", "all"}}})},
            {"analysis", {{"control", {{"type", "load"}, {"steps", 20}}}}}};
  tsm::Model model;
  const RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  bool pressed_column = false;
  for (const StepRecord& s : r.steps) {
    const tsm::solver::ContactPoint& c = contact_of(s);
    if (s.load_factor < 0.45 + 1e-12 && s.load_factor > 0.05) {
      ASSERT_GE(c.element, 0) << "step " << s.step;
      EXPECT_EQ(model.elements[c.element].member, 0) << "step " << s.step;  // on the column
      EXPECT_GT(c.force, 0.0);
      pressed_column = true;
    }
    if (s.load_factor > 0.55) {
      EXPECT_LT(c.element, 0) << "step " << s.step << ": still in contact above the beam";
      const int pusher = model.node_index(9);
      for (int k = 0; k < model.node_count(); ++k)
        if (k != pusher) EXPECT_LT(node_displacement(model, s, model.nodes[k].id).cwiseAbs().maxCoeff(), 1e-9) << "step " << s.step;
    }
  }
  EXPECT_TRUE(pressed_column);
}

TEST(ContactDetection, TwoContactsAtOnceMatchTheLinearFlexibility) {
  BeamSpec b;
  b.divisions = 40;
  b.A = 1e6;
  json m = pusher_model(b, 0.3, 0.0, 0.0, 1e-6, 1);
  m["nodes"].push_back({{"id", 101}, {"x", 0.7}, {"y", 0.0}});
  m["supports"].push_back({{"node", 101}, {"fix", {"ux", "rz"}}});
  m["prescribed"].push_back({{"node", 101}, {"uy", 4e-6}});
  m["contacts"].push_back({{"node", 101}, {"members", "all"}});
  tsm::Model model;
  const RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  // Cantilever flexibility (EI = 1): f_ij = a_i² (3 a_j − a_i) / 6 for a_i ≤ a_j.
  const double a1 = 0.3, a2 = 0.7;
  Eigen::Matrix2d F;
  F << a1 * a1 * a1 / 3.0, a1 * a1 * (3 * a2 - a1) / 6.0, a1 * a1 * (3 * a2 - a1) / 6.0, a2 * a2 * a2 / 3.0;
  const Eigen::Vector2d P = F.fullPivLu().solve(Eigen::Vector2d(1e-6, 4e-6));
  ASSERT_GT(P.minCoeff(), 0.0);
  EXPECT_NEAR(contact_of(r.steps.back(), 0).force, P[0], 1e-4 * P.norm());
  EXPECT_NEAR(contact_of(r.steps.back(), 1).force, P[1], 1e-4 * P.norm());
}

TEST(ContactDetection, BeamOnBeamMatchesTheSeriesSprings) {
  // A hanging post (clamped at its top, moved down) lands with its free bottom node on the
  // mid-span of a cantilever: the contact force compresses the post and bends the cantilever.
  BeamSpec b;
  b.divisions = 20;
  b.A = 1e6;
  json m = beam_model(b);
  m["nodes"].push_back({{"id", 10}, {"x", 0.5}, {"y", 1e-6}});
  m["nodes"].push_back({{"id", 11}, {"x", 0.5}, {"y", 0.5}});
  m["sections"]["post"] = {{"A", 2e-1}, {"I", 1.0}, {"shear_area", 1e3}};
  m["members"].push_back({{"from", 11}, {"to", 10}, {"divisions", 4}, {"material", "m"}, {"section", "post"}});
  m["supports"] = json::array({{{"node", 1}, {"type", "fixed"}}, {{"node", 11}, {"fix", {"ux", "rz"}}}});
  m["prescribed"] = json::array({{{"node", 11}, {"uy", -1.1e-5}}});
  m["contacts"] = json::array({{{"node", 10}, {"members", {0}}}});
  tsm::Model model;
  const RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  const double closing = 1e-5;                                   // 1.1e-5 minus the 1e-6 gap
  const double compliance = 0.125 / 3.0 + 0.5 / (1.0 * 2e-1);    // cantilever a³/3EI + post L/EA
  EXPECT_NEAR(contact_of(r.steps.back()).force, closing / compliance, 1e-4 * closing / compliance);
}

TEST(ContactDetection, ABeamTipDraggedAlongABeamEndsWhereAPushThereEnds) {
  // A cantilever (8 elements, from (2, 2) down to its tip just above a 20-element pinned beam at
  // x = 3.03) has its clamp moved 3 m along and 5 cm down: its tip, pressed onto the beam, slides
  // over six of the beam's nodes. Frictionless and elastic, it must end as the same cantilever
  // clamped at the end position from the start and only pushed down there. Before, the tip
  // stopped at the first beam node: the contact's blocks coupling the tip to the next element's
  // far node landed in an entry of the factor's fill, which the factorisation starts at zero,
  // so Newton ran on a tangent without them and diverged (then a pull released the contact at
  // a wild iterate, and the tip was accepted through the beam for the rest of the run).
  const auto model_of = [](double clamp_x, double move_x, int steps) {
    const auto member = [](int from, int to, int divisions) {
      return json{{"from", from}, {"to", to}, {"divisions", divisions}, {"element", "timoshenko"},
                  {"material", "steel"}, {"section", "s"}};
    };
    return json{{"materials", {{"steel", {{"E", 2e11}, {"G", 7.7e10}}}}},
                {"sections", {{"s", {{"A", 0.004}, {"I", 2e-5}, {"shear_area", 0.002}}}}},
                {"nodes", json::array({{{"id", 1}, {"x", 0.0}, {"y", 0.0}}, {{"id", 2}, {"x", 10.0}, {"y", 0.0}},
                                       {{"id", 5}, {"x", clamp_x}, {"y", 2.0}}, {{"id", 6}, {"x", clamp_x + 1.03}, {"y", 0.001}}})},
                {"members", json::array({member(1, 2, 20), member(5, 6, 8)})},
                {"supports", json::array({{{"node", 1}, {"type", "pinned"}}, {{"node", 2}, {"type", "pinned"}},
                                          {{"node", 5}, {"type", "fixed"}}})},
                {"prescribed", json::array({{{"node", 5}, {"ux", move_x}, {"uy", -0.05}}})},
                {"contacts", json::array({{{"node", 6}, {"members", {0}}}})},
                {"analysis", {{"control", {{"type", "load"}, {"steps", steps}}}}}};
  };
  tsm::Model pushed_model;
  const RunResult pushed = run(model_of(5.0, 0.0, 1), pushed_model);
  ASSERT_EQ(pushed.status, tsm::solver::Status::converged) << pushed.message;
  const tsm::solver::ContactPoint& there = contact_of(pushed.steps.back());
  ASSERT_GT(there.force, 1e4);
  const Eigen::Vector2d tip_there = node_position(pushed_model, pushed.steps.back(), 6);
  for (const int steps : {1, 20}) {
    tsm::Model model;
    const RunResult r = run(model_of(2.0, 3.0, steps), model);
    ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
    for (const StepRecord& s : r.steps) ASSERT_GE(contact_of(s).element, 0) << "step " << s.step << ": the tip left the beam";
    const tsm::solver::ContactPoint& c = contact_of(r.steps.back());
    EXPECT_EQ(c.element, there.element) << steps << " steps";
    EXPECT_NEAR(c.alpha, there.alpha, 1e-9) << steps << " steps";
    EXPECT_NEAR(c.force, there.force, 1e-9 * there.force) << steps << " steps";
    EXPECT_LT((node_position(model, r.steps.back(), 6) - tip_there).norm(), 1e-10) << steps << " steps";
    expect_equilibrium(model, r.steps.back());
  }
}

}  // namespace
