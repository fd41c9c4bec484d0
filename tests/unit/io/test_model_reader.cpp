// The model reader holds a model's run to a memory budget (io/model_reader, io/memory_budget):
// refused before the memory is spent — the elements before any is made — at the JSON path where
// most of it would go.
#include "tsmframe/io/model_reader.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "tsmframe/io/memory_budget.hpp"
#include "tsmframe/io/system_error.hpp"
#include "tsmframe/model/memory_estimate.hpp"

namespace test_model_reader {
namespace {

using nlohmann::json;

/// A cantilever of `divisions` elements with a tip load, `steps` load steps.
json cantilever(long divisions, int steps = 2) {
  return {{"materials", {{"steel", {{"E", 2e11}}}}},
          {"sections", {{"s", {{"A", 1e-2}, {"I", 1e-4}}}}},
          {"nodes", {{{"id", 1}, {"x", 0.0}, {"y", 0.0}}, {{"id", 2}, {"x", 4.0}, {"y", 0.0}}}},
          {"members", {{{"from", 1}, {"to", 2}, {"divisions", divisions}, {"material", "steel"}, {"section", "s"}}}},
          {"supports", {{{"node", 1}, {"type", "fixed"}}}},
          {"loads", {{{"node", 2}, {"fy", -1e3}}}},
          {"analysis", {{"control", {{"type", "load"}, {"steps", steps}}}}}};
}

/// What read_model says of `model` within `bytes` ("" if it reads it).
std::string refusal(const json& model, double bytes) {
  try {
    tsm::io::read_model(model, {bytes, "the test's budget"});
  } catch (const tsm::io::SystemError& e) {
    return e.what();
  }
  return "";
}

TEST(ModelReaderBudget, AModelWithinItIsRead) { EXPECT_EQ(refusal(cantilever(1000), 50e6), ""); }

TEST(ModelReaderBudget, ElementsAreRefusedBeforeAnyIsMade) {
  // 10⁷ elements: ~5.6 GB, refused before the members are meshed (~1 GB and seconds).
  EXPECT_EQ(refusal(cantilever(10'000'000), 100e6),
            "members: the run needs ~5.6 GB of memory (10,000,000 elements and 10,000,001 nodes 4.8 GB, the state of 1 "
            "step 800 MB, the program 6 MB), more than the test's budget");
}

TEST(ModelReaderBudget, TheStatesTheOutputKeepsAndTheStepsCount) {
  json all = cantilever(10'000, 1'000);  // 1,000 states of 10⁴ elements: 800 MB, below the 8 GB cap
  EXPECT_EQ(refusal(all, 100e6).rfind("analysis.output: the run needs ~811 MB of memory (the state of 1,000 steps 800 MB,", 0), 0u)
      << refusal(all, 100e6);
  json steps = cantilever(4, 1'000'000);  // a record per step: 424 MB
  steps["analysis"]["output"] = "last";
  EXPECT_EQ(refusal(steps, 100e6).rfind("analysis.control.steps: the run needs ~430 MB of memory (1,000,000 steps' records 424 MB,", 0), 0u)
      << refusal(steps, 100e6);
}

TEST(ModelReaderBudget, ContactsWithTheirCandidates) {
  // 2,001 contact nodes over a beam of 2,000 elements, 4·10⁶ candidates: ~50 MB, most of it the
  // sparse LU kept as the fallback past 32 contacts.
  json m = cantilever(2000);
  json nodes = json::array();
  for (int k = 0; k < 2001; ++k) {
    m["nodes"].push_back({{"id", 10 + k}, {"x", 4.0 * (k + 0.5) / 2001}, {"y", 1.0}});
    m["supports"].push_back({{"node", 10 + k}, {"type", "pinned"}});
    nodes.push_back(10 + k);
  }
  m["contacts"] = {{{"nodes", nodes}, {"members", "all"}}};
  const std::string why = refusal(m, 20e6);
  EXPECT_EQ(why.rfind("contacts: the run needs ~", 0), 0u) << why;
  // The part it names is the estimate's (model/memory_estimate, checked against hand sums there).
  const tsm::MemoryEstimate estimate = tsm::estimate_memory(tsm::model_counts(tsm::io::read_model(m, {1e12, "all"})));
  EXPECT_NE(why.find("2,001 contacts with 4,002,000 candidate elements " + tsm::io::bytes_text(estimate.contacts.bytes)),
            std::string::npos)
      << why;
}

// An editor's "$schema" key (docs/tsmframe-model.schema.json) is read past, as the schema allows.
TEST(ModelReader, ASchemaKeyIsAccepted) {
  json model = cantilever(4);
  model["$schema"] = "https://example.org/tsmframe-model.schema.json";
  EXPECT_EQ(refusal(model, 50e6), "");
}

}  // namespace

}  // namespace test_model_reader
