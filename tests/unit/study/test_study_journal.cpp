// A study's journal (study/study_journal.hpp): every field of a row comes back as written; a
// line cut short, a stopped case and a line that is no row are not rows; another study's journal
// is refused by path; the study's fingerprint follows its file and its model; the cases a
// journal holds are not run again.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "support/models.hpp"
#include "tsmframe/io/input_error.hpp"
#include "tsmframe/study/study_journal.hpp"

namespace test_study_journal {
namespace {

using nlohmann::json;
using namespace tsm::study;
namespace fs = std::filesystem;

json cantilever() {
  json m = tsm::test::beam_model({.divisions = 4});
  m["supports"] = json::array({{{"node", 1}, {"type", "fixed"}}});
  m["loads"] = json::array({{{"node", 2}, {"fy", 1e-4}}});
  return m;
}

Study three_cases() {
  return read_study({{"model", cantilever()},
                     {"sweep", json::parse(R"([{"name": "n", "path": "/members/0/divisions", "values": [2, 3, 4]}])")},
                     {"record", json::parse(R"([{"name": "tip", "quantity": "displacement", "node": 2, "dof": "uy"},
                                                {"name": "peak", "quantity": "load_factor", "of": "max"}])")}},
                    ".");
}

/// A row with every field set, a record NaN, a message with what JSON escapes.
CaseResult full_row(size_t index, const Study& study) {
  CaseResult row;
  row.index = index;
  row.choice = case_choice(study, index);
  row.status = "not-converged";
  row.steps = 7, row.iterations = 41, row.last_iterations = 12;
  row.load_factor = 0.1 + 0.2;  // not a short decimal: read back bit for bit
  row.negative_eigenvalues = 2;
  row.notes = "a note; another";
  row.seconds = 1.0 / 3.0;
  row.message = "no convergence \"here\"\nand a second line";
  row.contact_first_element = 3, row.contact_max_alpha_first = 0.7, row.contact_last_element = 5, row.contact_elements_passed = 2;
  row.recorded = {-1.25e-3, std::numeric_limits<double>::quiet_NaN()};
  return row;
}

class Journal : public ::testing::Test {
 protected:
  fs::path dir_ = fs::temp_directory_path() / ("tsmframe-journal-" + std::to_string(::getpid()));
  void SetUp() override { fs::create_directories(dir_); }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path path() const { return dir_ / journal_name; }
};

TEST_F(Journal, EveryFieldOfARowComesBackAsWritten) {
  const Study s = three_cases();
  const CaseResult written = full_row(1, s);
  { StudyJournal journal(path(), s, {written}); }
  const JournalRows read = read_journal(path(), s);
  ASSERT_EQ(read.rows.size(), 1u);
  EXPECT_EQ(read.skipped, 0u);
  const CaseResult& r = read.rows[0];
  EXPECT_EQ(r.index, 1u);
  EXPECT_EQ(r.choice, written.choice);
  EXPECT_EQ(r.status, written.status);
  EXPECT_EQ(r.converged, written.converged);
  EXPECT_EQ(r.steps, 7);
  EXPECT_EQ(r.iterations, 41);
  EXPECT_EQ(r.last_iterations, 12);
  EXPECT_EQ(r.load_factor, written.load_factor);
  EXPECT_EQ(r.negative_eigenvalues, 2);
  EXPECT_EQ(r.notes, written.notes);
  EXPECT_EQ(r.seconds, written.seconds);
  EXPECT_EQ(r.message, written.message);
  EXPECT_EQ(r.contact_first_element, 3);
  EXPECT_EQ(r.contact_max_alpha_first, 0.7);
  EXPECT_EQ(r.contact_last_element, 5);
  EXPECT_EQ(r.contact_elements_passed, 2);
  ASSERT_EQ(r.recorded.size(), 2u);
  EXPECT_EQ(r.recorded[0], -1.25e-3);
  EXPECT_TRUE(std::isnan(r.recorded[1]));
}

TEST_F(Journal, AStoppedCaseALineCutShortAndALineThatIsNoRowAreNotRows) {
  const Study s = three_cases();
  {
    StudyJournal journal(path(), s, {});
    CaseResult stopped = full_row(0, s);
    stopped.status = "interrupted";
    journal.append(stopped);  // left out: the case runs again
    journal.append(full_row(2, s));
  }
  {
    std::ofstream append(path(), std::ios::app);
    append << R"({"case": 9, "status": "converged"})" << '\n';  // past the study's cases
    append << row_json(full_row(1, s)).dump().substr(0, 40);      // cut short by a kill: no newline
  }
  const JournalRows read = read_journal(path(), s);
  ASSERT_EQ(read.rows.size(), 1u);
  EXPECT_EQ(read.rows[0].index, 2u);
  EXPECT_EQ(read.skipped, 2u);
}

TEST_F(Journal, AnotherStudysJournalIsRefusedByPath) {
  const Study s = three_cases();
  { StudyJournal journal(path(), s, {full_row(0, s)}); }
  json changed_model = cantilever();
  changed_model["loads"][0]["fy"] = 2e-4;
  const Study other = read_study({{"model", changed_model},
                                  {"sweep", json::parse(R"([{"name": "n", "path": "/members/0/divisions", "values": [2, 3, 4]}])")},
                                  {"record", json::parse(R"([{"name": "tip", "quantity": "displacement", "node": 2, "dof": "uy"},
                                                             {"name": "peak", "quantity": "load_factor", "of": "max"}])")}},
                                 ".");
  EXPECT_NE(other.fingerprint, s.fingerprint);
  try {
    read_journal(path(), other);
    FAIL() << "another study's rows were taken";
  } catch (const tsm::io::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path().string() + ": holds the rows of another study"), std::string::npos) << e.what();
  }
  std::ofstream(path()) << "a,b,c\n1,2,3\n";
  EXPECT_THROW(read_journal(path(), s), tsm::io::InputError) << "no journal";
}

TEST_F(Journal, TheFingerprintFollowsTheSweepAndIsTheSameForTheSameStudy) {
  const Study s = three_cases();
  EXPECT_EQ(s.fingerprint.size(), 16u);
  EXPECT_EQ(three_cases().fingerprint, s.fingerprint);
  const Study fewer = read_study({{"model", cantilever()},
                                  {"sweep", json::parse(R"([{"name": "n", "path": "/members/0/divisions", "values": [2, 3]}])")}},
                                 ".");
  EXPECT_NE(fewer.fingerprint, s.fingerprint);
}

TEST_F(Journal, TheCasesItHoldsAreNotRunAgain) {
  const Study s = three_cases();
  const std::vector<CaseResult> whole = run_study(s, 1, "");
  ASSERT_EQ(whole.size(), 3u);
  std::vector<size_t> run;
  const std::vector<CaseResult> resumed =
      run_study(s, 2, "", [&](const CaseResult& row) { run.push_back(row.index); }, nullptr, {full_row(1, s)});
  EXPECT_EQ(run.size(), 2u);
  EXPECT_EQ(std::count(run.begin(), run.end(), 1u), 0) << "case 2 was done";
  ASSERT_EQ(resumed.size(), 3u);
  EXPECT_EQ(resumed[1].message, full_row(1, s).message) << "its row as the journal had it";
  for (const size_t k : {0u, 2u}) {
    EXPECT_EQ(resumed[k].status, whole[k].status);
    EXPECT_EQ(resumed[k].recorded[0], whole[k].recorded[0]);
  }
}

}  // namespace

}  // namespace test_study_journal
