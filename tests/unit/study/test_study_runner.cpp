// Running a study's cases (study/study_runner.hpp): the cases in order, the first parameter
// varying slowest; each case's model the base model with its assignments; a case that cannot be
// run is a row; what the progress callback throws ends the sweep on the caller's thread; a
// study of more than a million cases is refused, not counted round to a small number.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "support/models.hpp"
#include "tsmframe/study/study_runner.hpp"

namespace test_study_runner {
namespace {

using nlohmann::json;
using namespace tsm::study;

/// A cantilever (EI = 1, L = 1, 4 elements) under a tip load of 1e-4.
json cantilever() {
  json m = tsm::test::beam_model({.divisions = 4});
  m["supports"] = json::array({{{"node", 1}, {"type", "fixed"}}});
  m["loads"] = json::array({{{"node", 2}, {"fy", 1e-4}}});
  return m;
}

Study study_of(const json& sweep) { return read_study({{"model", cantilever()}, {"sweep", sweep}}, "."); }

/// A study built in code whose parameters have these numbers of values.
Study with_value_counts(const std::vector<size_t>& counts) {
  Study s;
  for (size_t n : counts) s.parameters.push_back({"p", std::vector<std::string>(n, "v"), std::vector<std::vector<Assignment>>(n)});
  return s;
}

TEST(StudyRunner, CasesVaryTheFirstParameterSlowest) {
  const Study s = with_value_counts({2, 3});
  const std::vector<std::vector<size_t>> expected = {{0, 0}, {0, 1}, {0, 2}, {1, 0}, {1, 1}, {1, 2}};
  ASSERT_EQ(s.case_count(), expected.size());
  for (size_t k = 0; k < expected.size(); ++k) EXPECT_EQ(case_choice(s, k), expected[k]) << "case " << k;
}

TEST(StudyRunner, ACasesModelIsTheBaseModelWithItsAssignmentsInOrder) {
  const Study s = study_of(json::parse(R"([{"name": "n", "path": "/members/0/divisions", "values": [2, 8]},
                                           {"name": "v", "variants": [{"label": "a", "set": {"/analysis/max_iterations": 7}},
                                                                      {"label": "b", "set": {"/members/0/divisions": 5}}]}])"));
  EXPECT_EQ(case_model(s, {1, 0})["members"][0]["divisions"], 8);
  EXPECT_EQ(case_model(s, {1, 0})["analysis"]["max_iterations"], 7);
  EXPECT_EQ(case_model(s, {1, 1})["members"][0]["divisions"], 5) << "the later parameter's assignment wins";
  EXPECT_EQ(s.model["members"][0]["divisions"], 4) << "the base model is left as it is";
}

TEST(StudyRunner, EveryCaseIsARowInCaseOrderAndACaseThatCannotBeReadIsABadInputRow) {
  const Study s = study_of(json::parse(R"([{"name": "n", "path": "/members/0/divisions", "values": [2, 0, 3]}])"));
  const std::vector<CaseResult> rows = run_study(s, 2, "");
  ASSERT_EQ(rows.size(), 3u);
  for (size_t k = 0; k < rows.size(); ++k) {
    EXPECT_EQ(rows[k].index, k);
    EXPECT_EQ(rows[k].choice, std::vector<size_t>{k});
  }
  EXPECT_TRUE(rows[0].converged) << rows[0].message;
  EXPECT_TRUE(rows[2].converged) << rows[2].message;
  EXPECT_EQ(rows[1].status, "bad-input");
  EXPECT_EQ(rows[1].message.rfind("members[0].divisions: ", 0), 0u) << rows[1].message;
  EXPECT_EQ(rows[1].steps, 0);
  EXPECT_EQ(rows[0].steps, 1) << "the model's one load step";
  EXPECT_GE(rows[0].iterations, rows[0].last_iterations);
  EXPECT_EQ(rows[0].load_factor, 1.0);
}

TEST(StudyRunner, WhatTheProgressCallbackThrowsEndsTheSweepOnTheCallersThread) {
  const Study s = study_of(json::parse(R"([{"name": "n", "path": "/members/0/divisions", "values": [2, 3, 4, 5, 6, 7]}])"));
  int called = 0;
  const auto stop = [&](const CaseResult&) {
    ++called;
    throw std::runtime_error("stopped by the caller");
  };
  EXPECT_THROW(run_study(s, 2, "", stop), std::runtime_error);
  EXPECT_GE(called, 1);
  EXPECT_LE(called, 2) << "each thread stops after the case it is running";
}

TEST(StudyRunner, TheCaseCountIsRefusedPastAMillionEvenWhereTheProductWouldWrapToZero) {
  EXPECT_EQ(with_value_counts({1000, 1000}).case_count(), max_cases);
  EXPECT_THROW(with_value_counts({1001, 1000}).case_count(), std::length_error);
  EXPECT_THROW(with_value_counts({65536, 65536, 65536, 65536}).case_count(), std::length_error);  // 2⁶⁴
  EXPECT_EQ(with_value_counts({65536, 65536, 0}).case_count(), 0u) << "a parameter without values: no cases";
}

}  // namespace

namespace {

TEST(StudyShard, EveryCaseIsInExactlyOneShardAndEachCountsItsOwn) {
  for (const size_t total : {1u, 7u, 20u})
    for (const size_t count : {1u, 3u, 8u, 25u}) {
      std::vector<int> holders(total, 0);
      for (size_t index = 0; index < count; ++index) {
        const StudyShard shard{index, count};
        size_t held = 0;
        for (size_t k = 0; k < total; ++k)
          if (shard.holds(k)) ++holders[k], ++held;
        EXPECT_EQ(shard.cases(total), held) << index << '/' << count << " of " << total;
      }
      for (size_t k = 0; k < total; ++k) EXPECT_EQ(holders[k], 1) << "case " << k << ", " << count << " shards";
    }
}

TEST(StudyShard, AStudyRunsOnlyItsShardsCases) {
  const Study s = study_of(json::parse(R"([{"name": "n", "path": "/members/0/divisions", "values": [2, 3, 4, 5, 6]}])"));
  const std::vector<CaseResult> rows = run_study(s, 2, "", {}, nullptr, {}, StudyShard{1, 2});
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].index, 1u);
  EXPECT_EQ(rows[1].index, 3u);
  EXPECT_TRUE(run_study(s, 2, "", {}, nullptr, {}, StudyShard{6, 7}).empty()) << "a shard beyond the cases holds none";
}

}  // namespace

}  // namespace test_study_runner
