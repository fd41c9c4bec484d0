// `tsmframe study`: rows per case, failing cases as rows with exit 1, bad study input exit 2 with
// the JSON path; and the paper studies' regressions (studies/*.json).
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "support/cli.hpp"
#include <sstream>

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

using tsm::test::Outcome;
using tsm::test::run_cli;

class Study : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("tsmframe-study-" + std::to_string(::getpid()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string write(const std::string& name, const json& content) {
    std::ofstream(dir_ / name) << content.dump(2);
    return (dir_ / name).string();
  }
  json read_json(const fs::path& path) {
    std::ifstream in(path);
    return json::parse(in);
  }
  static json cantilever() {
    return json::parse(R"({
      "materials": {"m": {"E": 1.0, "G": 0.5}}, "sections": {"s": {"A": 1e4, "I": 1.0, "shear_area": 1e3}},
      "nodes": [{"id": 1, "x": 0, "y": 0}, {"id": 2, "x": 1, "y": 0}],
      "members": [{"from": 1, "to": 2, "divisions": 10, "material": "m", "section": "s"}],
      "supports": [{"node": 1, "type": "fixed"}],
      "loads": [{"node": 2, "fy": 1.0}],
      "analysis": {"control": {"type": "load", "steps": 1}, "cutback": false}})");
  }
  fs::path dir_;
};

TEST_F(Study, TwoCasesTwoRowsAndAFailingCaseIsARow) {
  json s = {{"format", "tsmframe-study/1"}, {"title", "two cases"}, {"model", cantilever()},
            {"sweep", json::array({{{"name", "allowed_iterations"}, {"path", "/analysis/max_iterations"}, {"values", {50, 1}}}})}};
  const std::string file = write("study.json", s);
  const Outcome o = run_cli("study " + file + " --out " + (dir_ / "out").string());
  EXPECT_EQ(o.exit_code, 1) << o.output;  // one Newton iteration, without cutback, does not reach PL²/EI = 1
  const json r = read_json(dir_ / "out" / "study.json");
  ASSERT_EQ(r["cases"].size(), 2u);
  EXPECT_EQ(r["cases"][0]["allowed_iterations"], "50");
  EXPECT_TRUE(r["cases"][0]["converged"].get<bool>());
  EXPECT_FALSE(r["cases"][1]["converged"].get<bool>());
  EXPECT_NE(r["cases"][1]["message"].get<std::string>(), "");
  std::ifstream csv(dir_ / "out" / "study.csv");
  std::string line;
  int lines = 0;
  while (std::getline(csv, line)) ++lines;
  EXPECT_EQ(lines, 3);
}

TEST_F(Study, ABadCaseModelIsARowNotACrash) {
  json s = {{"model", cantilever()},
            {"sweep", json::array({{{"name", "divisions"}, {"path", "/members/0/divisions"}, {"values", {4, 0}}}})}};
  const Outcome o = run_cli("study " + write("study.json", s) + " --out " + (dir_ / "out").string() + " -q");
  EXPECT_EQ(o.exit_code, 1) << o.output;
  const json r = read_json(dir_ / "out" / "study.json");
  ASSERT_EQ(r["cases"].size(), 2u);
  EXPECT_EQ(r["cases"][1]["status"], "bad-input");
  EXPECT_NE(r["cases"][1]["message"].get<std::string>().find("members[0].divisions"), std::string::npos);
  // The summary tells the invalid case from one that did not converge, with its reason.
  EXPECT_NE(o.output.find("2 cases, 0 did not converge, 1 had a model the sweep made invalid (bad-input; case 2: "
                          "members[0].divisions"),
            std::string::npos)
      << o.output;
}

TEST_F(Study, BadStudyInputExitsTwoWithThePath) {
  struct Bad {
    const char* sweep;
    std::string expected;
  };
  const std::vector<Bad> cases = {
      {R"([{"name": "n", "path": "members/0/divisions", "values": [1]}])", "sweep[0].path: not a JSON pointer"},
      {R"([{"name": "n", "path": "/members/0/divisions"}])", "sweep[0]: give exactly one of \"values\" and \"range\""},
      {R"([{"name": "n", "path": "/x", "range": [5, 2]}])", "sweep[0].range[1]: must not be below from"},
      {R"([{"name": "v", "variants": [{"label": "a"}]}])", "sweep[0].variants[0].set: missing"},
      {R"([{"name": "n", "path": "/x", "values": [1], "colour": 1}])", "sweep[0].colour: unknown key"},
  };
  for (const Bad& b : cases) {
    json s = {{"model", cantilever()}};
    s["sweep"] = json::parse(b.sweep);
    const std::string file = write("bad.json", s);
    const Outcome o = run_cli("study " + file + " --out " + (dir_ / "out").string());
    EXPECT_EQ(o.exit_code, 2) << o.output;
    EXPECT_NE(o.output.find(file + ": " + b.expected), std::string::npos) << o.output;
    EXPECT_FALSE(fs::exists(dir_ / "out"));
  }
}

// ---- The paper's studies (studies/): regressions ----

TEST_F(Study, Fig3TimoshenkoCircleConvergesForEveryMeshAtLOverH20) {
  const Outcome o = run_cli(std::string("study ") + TSMFRAME_SOURCE_DIR "/studies/fig3-circle.json -q --out " + (dir_ / "fig3").string());
  ASSERT_TRUE(o.exit_code == 0 || o.exit_code == 1) << o.output;
  const json r = read_json(dir_ / "fig3" / "study.json");
  int timoshenko_20 = 0, eb_100_failed = 0;
  for (const json& c : r["cases"]) {
    const std::string setup = c["setup"], element = c["element"];
    if (setup.find("L/h=20") != std::string::npos && element == "timoshenko") {
      ++timoshenko_20;
      EXPECT_TRUE(c["converged"].get<bool>()) << setup << " n = " << c["divisions"].get<std::string>();
    }
    if (setup.find("L/h=100") != std::string::npos && element == "euler-bernoulli" && !c["converged"].get<bool>() &&
        std::stoi(c["divisions"].get<std::string>()) <= 200)
      ++eb_100_failed;
  }
  EXPECT_EQ(timoshenko_20, 2 * (195 + 16));  // both set-ups, meshes 6 … 200 and 250 … 1000
  EXPECT_GT(eb_100_failed, 0);               // the paper's finding: Euler–Bernoulli breaks down on fine meshes
}

TEST_F(Study, Fig7ContactPointPassesAnElementEndForBothFormulations) {
  const Outcome o = run_cli(std::string("study ") + TSMFRAME_SOURCE_DIR "/studies/fig7-contact-edge.json -q --out " + (dir_ / "fig7").string());
  ASSERT_TRUE(o.exit_code == 0 || o.exit_code == 1) << o.output;
  const json r = read_json(dir_ / "fig7" / "study.json");
  std::map<std::string, int> passed;
  for (const json& c : r["cases"])
    if (c["treatment"] == "tsmframe") {
      EXPECT_TRUE(c["converged"].get<bool>()) << c.dump();
      if (c["contact_elements_passed"].get<int>() >= 1) ++passed[c["frame"].get<std::string>() + " " + c["element"].get<std::string>()];
    }
  for (const char* f : {"chord euler-bernoulli", "chord timoshenko", "cantilever euler-bernoulli", "cantilever timoshenko"})
    EXPECT_EQ(passed[f], 6) << f;  // every position, all four formulations
  EXPECT_TRUE(fs::exists(dir_ / "fig7" / "cases" / "1" / "steps.csv"));  // "keep": every case's results
}

}  // namespace
