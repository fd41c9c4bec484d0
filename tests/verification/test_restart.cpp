// Restart (issue 29): a run goes on from a kept step of an earlier run of the same model
// (results.json's step "state": path parameter, chord rotations, contacts, a stage's start) and
// ends exactly where the uninterrupted run does — bit for bit where the path is the same: under
// load and displacement control, with a contact sliding through element ends, in either stage of
// a staged run. Results of another model, a step without state and arc-length control are
// refused with their JSON path.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "support/contact_models.hpp"
#include "support/models.hpp"
#include "tsmframe/io/input_error.hpp"
#include "tsmframe/io/restart_reader.hpp"
#include "tsmframe/io/results_writer.hpp"

namespace test_restart {
namespace {

using namespace tsm::test;

/// The results.json a run writes, parsed.
json results_json(const tsm::Model& model, const tsm::solver::RunResult& result) {
  std::ostringstream out;
  tsm::io::write_results_json(out, model, result);
  return json::parse(out.str());
}

/// Runs `m` whole, then again from its step `from` (0: the middle step with state): every step
/// after it must be the same bit for bit (displacements, λ, iterations, contact points).
void expect_restart_equals_whole_run(const json& m, int from) {
  tsm::Model model;
  const tsm::solver::RunResult whole = run(m, model);
  ASSERT_EQ(whole.status, tsm::solver::Status::converged) << whole.message;
  if (from == 0) {
    std::vector<int> kept;
    for (const auto& s : whole.steps)
      if (s.has_state) kept.push_back(s.step);
    from = kept[kept.size() / 2];
  }
  const tsm::solver::RestartPoint point = tsm::io::read_restart(results_json(model, whole), from, model);
  const tsm::solver::RunResult restarted = tsm::solver::run_analysis(model, {}, nullptr, &point);
  ASSERT_EQ(restarted.status, tsm::solver::Status::converged) << restarted.message;
  ASSERT_EQ(restarted.steps.size(), whole.steps.size() - from);
  for (size_t k = 0; k < restarted.steps.size(); ++k) {
    const tsm::solver::StepRecord &a = restarted.steps[k], &b = whole.steps[from + k];
    EXPECT_EQ(a.step, b.step);
    EXPECT_EQ(a.stage, b.stage);
    EXPECT_EQ(a.load_factor, b.load_factor) << "step " << b.step;
    EXPECT_EQ(a.iterations, b.iterations) << "step " << b.step;
    EXPECT_TRUE(a.displacements == b.displacements) << "step " << b.step << ": differs by "
                                                    << (a.displacements - b.displacements).lpNorm<Eigen::Infinity>();
    ASSERT_EQ(a.contacts.size(), b.contacts.size());
    for (size_t c = 0; c < a.contacts.size(); ++c) {
      EXPECT_EQ(a.contacts[c].element, b.contacts[c].element) << "step " << b.step;
      EXPECT_EQ(a.contacts[c].alpha, b.contacts[c].alpha) << "step " << b.step;
      EXPECT_EQ(a.contacts[c].force, b.contacts[c].force) << "step " << b.step;
    }
  }
}

json cantilever(json control) {
  json m = beam_model({});
  m["supports"] = json::array({{{"node", 1}, {"type", "fixed"}}});
  m["loads"] = json::array({{{"node", 2}, {"fy", 4.0}}});  // P L²/EI = 4: the tip turns ~1.2 rad
  m["analysis"] = {{"control", control}};
  return m;
}

TEST(Restart, ALoadControlledElasticaGoesOnBitForBit) {
  expect_restart_equals_whole_run(cantilever({{"type", "load"}, {"steps", 8}}), 3);
  // A load path with legs (load, unload): the path parameter, not λ, says where it is.
  expect_restart_equals_whole_run(cantilever({{"type", "load"}, {"steps", 3}, {"path", {1.0, 0.25}}}), 4);
  // Every second step kept: the restarted run keeps the same steps (numbered on, not from 1).
  json every_second = cantilever({{"type", "load"}, {"steps", 8}});
  every_second["analysis"]["output"] = 2;
  expect_restart_equals_whole_run(every_second, 4);
}

TEST(Restart, ADisplacementControlledRunGoesOnBitForBit) {
  expect_restart_equals_whole_run(cantilever({{"type", "displacement"}, {"node", 2}, {"dof", "uy"}, {"target", 0.7}, {"steps", 7}}), 2);
}

TEST(Restart, AContactSlidingThroughElementEndsGoesOnBitForBit) {
  // A rigid pusher drives a cantilever's contact point through element ends (contact-push).
  expect_restart_equals_whole_run(pusher_model({}, 0.45, 0.0, 0.0, 0.4, 12), 5);
  expect_restart_equals_whole_run(pusher_model({}, 0.45, 0.0, 0.0, 0.4, 12), 1);
}

TEST(Restart, EitherStageOfAStagedRunGoesOnBitForBit) {
  // Press a roller into a cantilever, then slide it along (test_stages.cpp): from a step of
  // stage 1 (its start held for stage 2's absolute targets) and from one of stage 2.
  json m = beam_model({});
  m.erase("analysis");
  m["supports"] = json::array({{{"node", 1}, {"type", "fixed"}}});
  m["nodes"].push_back({{"id", 100}, {"x", 0.45}, {"y", 0.0}});
  m["contacts"] = json::array({{{"node", 100}, {"members", "all"}}});
  m["stages"] = json::array(
      {{{"prescribed", json::array({{{"node", 100}, {"ux", 0.0}, {"uy", -0.05}}})}, {"control", {{"type", "load"}, {"steps", 4}}}},
       {{"loads", json::array({{{"node", 2}, {"fy", 0.3}}})},
        {"prescribed", json::array({{{"node", 100}, {"ux", 0.3}}})},
        {"control", {{"type", "load"}, {"steps", 8}}}}});
  expect_restart_equals_whole_run(m, 2);
  expect_restart_equals_whole_run(m, 4);  // the end of stage 1
  expect_restart_equals_whole_run(m, 7);
}

json example(const char* name) {
  return json::parse(std::ifstream(std::filesystem::path(TSMFRAME_SOURCE_DIR) / "examples" / name));
}

TEST(Restart, AnArcLengthPathGoesOnBitForBitPastItsLimitPoints) {
  // The step's arc-length memory (the next Δs, the last increment that steers the predictor)
  // is kept with it: Williams' toggle and Lee's frame past their limit points, and a contact
  // sliding along a cantilever, from the middle kept step of each.
  expect_restart_equals_whole_run(example("williams-toggle-arc-length.json"), 0);
  expect_restart_equals_whole_run(example("lee-frame-arc-length.json"), 0);
  expect_restart_equals_whole_run(example("cantilever-on-cantilever-arc-length.json"), 0);
}

TEST(Restart, WhatCannotGoOnIsRefusedWithItsPath) {
  const json m = cantilever({{"type", "load"}, {"steps", 4}});
  tsm::Model model;
  const json results = results_json(model, run(m, model));
  const auto refusal = [&](const json& r, int step, const tsm::Model& to) -> std::string {
    try {
      tsm::io::read_restart(r, step, to);
    } catch (const tsm::io::InputError& e) {
      return e.what();
    }
    return "(accepted)";
  };
  EXPECT_EQ(refusal(results, 9, model), "steps: no step 9 in these results");
  json moved = m;
  moved["nodes"][1]["x"] = 1.5;
  tsm::Model other = tsm::io::read_model(moved);
  EXPECT_NE(refusal(results, 0, other).find("nodes[1]: results of another model"), std::string::npos) << refusal(results, 0, other);
  json finer = m;
  finer["members"][0]["divisions"] = 12;
  other = tsm::io::read_model(finer);
  EXPECT_NE(refusal(results, 0, other).find("results of another model"), std::string::npos) << refusal(results, 0, other);
  json arc = m;
  arc["analysis"]["control"] = {{"type", "arc-length"}, {"initial_increment", 0.1}, {"max_steps", 5}};
  other = tsm::io::read_model(arc);
  EXPECT_NE(refusal(results, 0, other).find("state.arc_length: the step was not taken under arc-length control"), std::string::npos)
      << refusal(results, 0, other);
  json last_only = m;
  last_only["analysis"]["output"] = "last";
  tsm::Model last_model;
  const json last_results = results_json(last_model, run(last_only, last_model));
  EXPECT_NE(refusal(last_results, 2, last_model).find("steps[1]: step 2 carries no state"), std::string::npos)
      << refusal(last_results, 2, last_model);
  EXPECT_EQ(refusal(last_results, 0, last_model), "(accepted)");  // the newest step with state: the last
  json staged = m;
  staged.erase("loads");
  staged["analysis"].erase("control");
  staged["stages"] = json::array({{{"loads", json::array({{{"node", 2}, {"fy", 1.0}}})}}});
  other = tsm::io::read_model(staged);
  EXPECT_NE(refusal(results, 0, other).find("results of a run without stages"), std::string::npos) << refusal(results, 0, other);
  EXPECT_NE(refusal(json{{"format", "something"}}, 0, model).find("format: not a tsmframe results file"), std::string::npos);
}

}  // namespace

}  // namespace test_restart
