// The stop request (solver/stop_request.hpp): a run asked to stop ends before its next attempt
// with status interrupted, every converged step kept, and says where it stopped.
#include <gtest/gtest.h>

#include <sstream>

#include "support/models.hpp"
#include "tsmframe/io/results_writer.hpp"

namespace test_stop_request {
namespace {

using tsm::test::json;

/// A cantilever of 10 elements under a tip load, in `steps` load steps (or arc-length steps).
json cantilever(bool arc_length = false) {
  json m = tsm::test::beam_model({});
  m["supports"] = json::array({{{"node", 1}, {"type", "fixed"}}});
  m["loads"] = json::array({{{"node", 2}, {"fy", 0.5}}});
  m["analysis"]["control"] = arc_length ? json{{"type", "arc-length"}, {"initial_increment", 0.01}, {"max_steps", 10}}
                                        : json{{"type", "load"}, {"steps", 10}};
  return m;
}

TEST(StopRequest, ARunAskedBeforeItsFirstStepHasNoStepAndSaysSo) {
  const tsm::Model model = tsm::io::read_model(cantilever());
  tsm::solver::StopRequest stop;
  stop.request();
  const tsm::solver::RunResult result = tsm::solver::run_analysis(model, {}, &stop);
  EXPECT_EQ(result.status, tsm::solver::Status::interrupted);
  EXPECT_TRUE(result.steps.empty());
  EXPECT_EQ(result.message, "interrupted on request before the first step");
  std::ostringstream out;  // results.json of no step
  tsm::io::write_results_json(out, model, result);
  EXPECT_NE(out.str().find("\"status\":\"interrupted\""), std::string::npos);
}

TEST(StopRequest, EachControlStopsAfterTheStepThatAskedKeepingEveryConvergedStep) {
  for (const bool arc_length : {false, true}) {
    const tsm::Model model = tsm::io::read_model(cantilever(arc_length));
    tsm::solver::StopRequest stop;
    const tsm::solver::RunResult result = tsm::solver::run_analysis(
        model, [&](const tsm::solver::StepRecord& step) { if (step.step == 3) stop.request(); }, &stop);
    EXPECT_EQ(result.status, tsm::solver::Status::interrupted) << arc_length;
    EXPECT_STREQ(tsm::solver::status_name(result.status), "interrupted");
    ASSERT_EQ(result.steps.size(), 3u) << arc_length;
    for (const tsm::solver::StepRecord& step : result.steps) EXPECT_TRUE(step.converged);
    EXPECT_TRUE(result.steps.back().has_state);
    EXPECT_EQ(result.failure.kind, tsm::solver::RunFailure::Kind::interrupted);
    std::ostringstream expected;
    expected << "interrupted on request before step 4 (the last converged step at load factor "
             << result.steps.back().load_factor << ")";
    EXPECT_EQ(result.message, expected.str());
  }
}

}  // namespace

}  // namespace test_stop_request
