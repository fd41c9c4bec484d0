// `tsmframe study`: rows per case, failing cases as rows with exit 1, bad study input exit 2 with
// the JSON path; and the paper studies' regressions (studies/*.json).
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "support/cli.hpp"
#include "support/scratch_directory.hpp"
#include <sstream>

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

using tsm::test::Outcome;
using tsm::test::run_cli;
using tsm::test::run_cli_bounded;
using tsm::test::run_command;

constexpr long test_memory_kb = 2'000'000;  // what a study run by these tests may take: 2 GB …
constexpr int test_seconds = 60;            // … and a minute (each takes well under a second)

class Study : public tsm::test::ScratchDirectory {
 protected:
  Study() : ScratchDirectory("tsmframe-study-") {}
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
  /// The study file `s` is refused: exit 2, one line `FILE: expected…`, nothing written — within
  /// bounded memory and time, so that a study that would allocate without end fails here.
  void expect_refused(const json& s, const std::string& expected) {
    const std::string file = write("bad.json", s);
    const Outcome o = run_cli_bounded("study " + file + " --out " + (dir_ / "out").string(), test_memory_kb, test_seconds);
    EXPECT_EQ(o.exit_code, 2) << o.output;
    EXPECT_EQ(o.output.rfind(file + ": " + expected, 0), 0u) << o.output;
    EXPECT_EQ(std::count(o.output.begin(), o.output.end(), '\n'), 1) << o.output;
    EXPECT_FALSE(fs::exists(dir_ / "out"));
  }
  /// The study with the cantilever and `sweep`.
  static json study(const char* sweep) { return {{"model", cantilever()}, {"sweep", json::parse(sweep)}}; }
};

TEST_F(Study, TwoCasesTwoRowsAndAFailingCaseIsARow) {
  json s = {{"format", "tsmframe-study/1"}, {"title", "two cases"}, {"model", cantilever()},
            {"sweep", json::array({{{"name", "allowed_iterations"}, {"path", "/analysis/max_iterations"}, {"values", {50, 1}}}})}};
  const std::string file = write("study.json", s);
  const Outcome o = run_cli("study " + file + " --out " + (dir_ / "out").string());
  EXPECT_EQ(o.exit_code, 1) << o.output;  // one Newton iteration, without cutback, does not reach PL²/EI = 1
  const json r = read_json(dir_ / "out" / "study.json");
  ASSERT_EQ(r["cases"].size(), 2u);
  EXPECT_EQ(r["cases"][0]["allowed_iterations"], 50);  // the number the sweep gave
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
  EXPECT_TRUE(r["cases"][0]["converged"].get<bool>()) << r["cases"][0].dump();
  EXPECT_EQ(r["cases"][1]["status"], "bad-input");
  const std::string reason = r["cases"][1]["message"];
  EXPECT_EQ(reason.rfind("members[0].divisions: ", 0), 0u) << reason;
  // The summary tells the invalid case from one that did not converge, with its reason: its
  // counts are those of the rows written.
  int not_converged = 0, invalid = 0;
  for (const json& c : r["cases"]) {
    not_converged += !c["converged"].get<bool>();
    invalid += c["status"] == "bad-input";
  }
  EXPECT_NE(o.output.find(std::to_string(r["cases"].size()) + " cases, " + std::to_string(not_converged - invalid) +
                          " did not converge, " + std::to_string(invalid) +
                          " had a model the sweep made invalid (bad-input; case 2: " + reason + ")"),
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
      {R"([{"name": "status", "path": "/x", "values": [1]}])", "sweep[0].name: \"status\" names another column already"},
      {R"([{"name": "", "path": "/x", "values": [1]}])", "sweep[0].name: empty"},
      {R"([{"name": "n", "path": "/x", "values": [1]}, {"name": "n", "path": "/y", "values": [2]}])",
       "sweep[1].name: \"n\" names another column already"},
  };
  for (const Bad& b : cases) {
    json s = {{"model", cantilever()}};
    s["sweep"] = json::parse(b.sweep);
    expect_refused(s, b.expected);
  }
}

TEST_F(Study, RecordedQuantitiesAreColumnsOfEveryCase) {
  // A cantilever (EI = 1, L = 1) under a tip load of 1e-4, loaded and unloaded (a load path 1 → 0,
  // 4 steps a leg), meshed with 2, 5 and 10 elements: the tip named by its coordinates (its id
  // changes with the mesh) deflects PL³/3EI at the peak — an Euler–Bernoulli mesh is exact at its
  // nodes for a tip load, to the 1e-4 geometric effect — and is back at 0 at the end; the clamp's
  // reaction balances the load (to the tolerance); λ peaks at 1.
  json m = cantilever();
  m["loads"][0]["fy"] = 1e-4;
  m["analysis"]["control"] = {{"type", "load"}, {"steps", 4}, {"path", {1.0, 0.0}}};
  json s = {{"model", m},
            {"sweep", json::array({{{"name", "divisions"}, {"path", "/members/0/divisions"}, {"values", {2, 5, 10}}}})},
            {"record", json::array({{{"name", "tip_uy_max"}, {"quantity", "displacement"}, {"node", {1.0, 0.0}}, {"dof", "uy"}, {"of", "max"}},
                                    {{"name", "tip_uy"}, {"quantity", "displacement"}, {"node", {1.0, 0.0}}, {"dof", "uy"}},
                                    {{"name", "clamp_Ry_min"}, {"quantity", "reaction"}, {"node", 1}, {"dof", "uy"}, {"of", "min"}},
                                    {{"name", "peak"}, {"quantity", "load_factor"}, {"of", "max"}}})}};
  const Outcome o = run_cli("study " + write("study.json", s) + " --out " + (dir_ / "out").string() + " -q");
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const json r = read_json(dir_ / "out" / "study.json");
  ASSERT_EQ(r["cases"].size(), 3u);
  for (const json& c : r["cases"]) {
    EXPECT_NEAR(c["tip_uy_max"].get<double>(), 1e-4 / 3.0, 1e-4 * 1e-4 / 3.0) << c.dump();
    EXPECT_NEAR(c["tip_uy"].get<double>(), 0.0, 1e-12) << c.dump();
    EXPECT_NEAR(c["clamp_Ry_min"].get<double>(), -1e-4, 1e-11) << c.dump();
    EXPECT_EQ(c["peak"].get<double>(), 1.0) << c.dump();
  }
  std::ifstream csv(dir_ / "out" / "study.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_NE(header.find(",tip_uy_max,tip_uy,clamp_Ry_min,peak,notes,message"), std::string::npos) << header;
}

TEST_F(Study, ARecordThatACaseCannotGiveIsABadInputRow) {
  // The tip at x = 1 exists in every mesh; x = 0.5 only where the mesh has a node there; a free
  // dof has no reaction; a node that is no contact node has no contact force.
  json s = {{"model", cantilever()},
            {"sweep", json::array({{{"name", "divisions"}, {"path", "/members/0/divisions"}, {"values", {2, 3}}}})},
            {"record", json::array({{{"name", "mid_uy"}, {"quantity", "displacement"}, {"node", {0.5, 0.0}}, {"dof", "uy"}}})}};
  Outcome o = run_cli("study " + write("study.json", s) + " --out " + (dir_ / "out").string() + " -q");
  EXPECT_EQ(o.exit_code, 1) << o.output;
  json r = read_json(dir_ / "out" / "study.json");
  EXPECT_EQ(r["cases"][0]["status"], "converged");
  EXPECT_TRUE(r["cases"][0]["mid_uy"].is_number());
  EXPECT_EQ(r["cases"][1]["status"], "bad-input");
  EXPECT_TRUE(r["cases"][1]["mid_uy"].is_null());
  EXPECT_EQ(r["cases"][1]["message"], "record[0].node: no node at [0.5, 0] (the nearest, node 4, is at [0.666667, 0], 0.166667 away)");
  s["record"] = json::array({{{"name", "R"}, {"quantity", "reaction"}, {"node", 2}, {"dof", "uy"}},
                             {{"name", "F"}, {"quantity", "contact_force"}, {"node", 2}}});
  o = run_cli("study " + write("study.json", s) + " --out " + (dir_ / "out2").string() + " -q");
  r = read_json(dir_ / "out2" / "study.json");
  EXPECT_EQ(r["cases"][0]["message"], "record[0].dof: node 2's uy is free: it has no reaction");
  s["record"].erase(0);
  o = run_cli("study " + write("study.json", s) + " --out " + (dir_ / "out3").string() + " -q");
  r = read_json(dir_ / "out3" / "study.json");
  EXPECT_EQ(r["cases"][0]["message"], "record[0].node: node 2 is no contact node");
}

TEST_F(Study, BadRecordsExitTwoWithThePath) {
  struct Bad {
    const char* record;
    std::string expected;
  };
  const std::vector<Bad> cases = {
      {R"([{"name": "x", "quantity": "stress"}])", "record[0].quantity: unknown quantity \"stress\""},
      {R"([{"name": "x", "quantity": "displacement", "node": 2}])", "record[0].dof: missing (required for displacement"},
      {R"([{"name": "x", "quantity": "displacement", "node": 2, "dof": "uz"}])", "record[0].dof: unknown dof \"uz\""},
      {R"([{"name": "x", "quantity": "load_factor", "of": "mean"}])", "record[0].of: expected \"last\", \"max\""},
      {R"([{"name": "status", "quantity": "load_factor"}])", "record[0].name: \"status\" names another column already"},
      {R"([{"name": "n", "quantity": "load_factor"}])", "record[0].name: \"n\" names another column already"},
      {R"([{"name": "x", "quantity": "reaction", "node": "tip", "dof": "uy"}])", "record[0].node: expected a node id or [x, y]"},
  };
  for (const Bad& b : cases) {
    json s = {{"model", cantilever()}, {"sweep", json::parse(R"([{"name": "n", "path": "/members/0/divisions", "values": [2]}])")}};
    s["record"] = json::parse(b.record);
    expect_refused(s, b.expected);
  }
}

// ---- Sweeps that must end with one line and exit 2, never an abort or a silent 0 ----

TEST_F(Study, APointerPastAListsEndIsRefusedWithoutBuildingTheList) {
  // Assigning at /nodes/4000000000 would resize the 2-node list to 4·10⁹ entries (64 GB).
  expect_refused(study(R"([{"name": "x", "path": "/nodes/4000000000", "values": [1]}])"),
                 "sweep[0].path: \"/nodes\" has 2 entries: 4000000000 is past its end (0 to 1 name them, 2 appends one)");
  expect_refused(study(R"([{"name": "x", "path": "/nodes/100000000/x", "values": [1]}])"),
                 "sweep[0].path: \"/nodes\" has 2 entries: 100000000 is past its end (0 to 1 name them)");
  expect_refused(study(R"([{"name": "x", "path": ["/members/0/divisions", "/loads/99999999999999999999999"], "values": [2]}])"),
                 "sweep[0].path[1]: \"/loads\" has 1 entry: 99999999999999999999999 is past its end (0 names it, 1 appends one)");
  expect_refused(study(R"([{"name": "v", "variants": [{"label": "far", "set": {"/supports/7": {"node": 2, "type": "fixed"}}}]}])"),
                 "sweep[0].variants[0].set[\"/supports/7\"]: \"/supports\" has 1 entry: 7 is past its end (0 names it, 1 appends one)");
  // A new key's list: /extra/values/4000000000 would make one of 4·10⁹ entries (found by fuzzing).
  expect_refused(study(R"([{"name": "x", "path": "/extra/values/4000000000", "values": [1]}])"),
                 "sweep[0].path: \"/extra/values\" is new: it would be made a list, where 4000000000 is past the end of its one entry (0 or \"-\" makes it)");
}

TEST_F(Study, APointerThatNamesNoEntryOfAListOrGoesIntoANumberIsRefused) {
  expect_refused(study(R"([{"name": "s", "path": "/nodes/x", "values": [2]}])"),
                 "sweep[0].path: \"/nodes\" is a list: \"x\" is no index of it (0, 1, …)");
  expect_refused(study(R"([{"name": "s", "path": "/members/0/divisions/2", "values": [2]}])"),
                 "sweep[0].path: \"/members/0/divisions\" is a number: it has no \"2\"");
}

TEST_F(Study, AMisspeltKeyIsMadeAndTheModelReaderRefusesIt) {
  // An object may gain keys at any depth (a base model may leave "analysis" out and a sweep set
  // /analysis/max_iterations); a misspelt one is the model's unknown key — in the only case, so
  // the study is bad input up front.
  json s = study(R"([{"name": "s", "path": "/analysis/contorl/steps", "values": [2]}])");
  expect_refused(s, "model: analysis.contorl: unknown key \"contorl\"");
}

TEST_F(Study, ABaseModelInvalidWhereNoParameterReachesIsRefusedUpFront) {
  // A typo the sweep does not touch makes every case bad input: refused before any case runs
  // (the first and the last case are read), not a study of bad-input rows with exit 1.
  json s = study(R"([{"name": "n", "path": "/members/0/divisions", "values": [2, 4, 8]}])");
  s["model"]["members"][0]["material"] = "stel";
  expect_refused(s, "model: members[0].material: unknown material \"stel\"");
  // Where the sweep mends the first case's fault in a later case, the cases run (rows say which).
  json mended = study(R"([{"name": "E", "path": "/materials/m/E", "values": [0, 1.0]}])");
  const Outcome o = run_cli("study " + write("mended.json", mended) + " --out " + (dir_ / "out").string() + " -q");
  EXPECT_EQ(o.exit_code, 1) << o.output;
  const json r = read_json(dir_ / "out" / "study.json");
  EXPECT_EQ(r["cases"][0]["status"], "bad-input");
  EXPECT_TRUE(r["cases"][1]["converged"].get<bool>());
}

TEST_F(Study, APointerMayNameANewKeyOrAppendOneEntry) {
  // /analysis/max_iterations is a new key of "analysis"; /members/0/load/fy makes the member's
  // "load" holding it; /loads/1 and /loads/- append a load.
  json s = study(R"([{"name": "setup", "variants": [
      {"label": "iterations", "set": {"/analysis/max_iterations": 20}},
      {"label": "member load", "set": {"/members/0/load/fy": 0.01}},
      {"label": "second load", "set": {"/loads/1": {"node": 2, "fx": 0.01}}},
      {"label": "appended", "set": {"/loads/-": {"node": 2, "fx": 0.01}}}]}])");
  const Outcome o = run_cli_bounded("study " + write("study.json", s) + " --out " + (dir_ / "out").string() + " -q",
                                    test_memory_kb, test_seconds);
  EXPECT_EQ(o.exit_code, 0) << o.output;
  const json r = read_json(dir_ / "out" / "study.json");
  ASSERT_EQ(r["cases"].size(), 4u);
  for (const json& c : r["cases"]) EXPECT_EQ(c["status"], "converged") << c.dump();
}

TEST_F(Study, APointerAnotherAssignmentMayMakeIsCheckedInEachCase) {
  // /loads/0/fy names a load only where the first parameter leaves one: the case that empties
  // "loads" is a bad-input row saying why, the other converges, and nothing is allocated.
  json s = study(R"([{"name": "loads", "variants": [{"label": "none", "set": {"/loads": []}},
                                                    {"label": "tip", "set": {"/loads": [{"node": 2, "fy": 1.0}]}}]},
                     {"name": "fy", "path": "/loads/0/fy", "values": [0.5]}])");
  const Outcome o = run_cli_bounded("study " + write("study.json", s) + " --out " + (dir_ / "out").string() + " -q",
                                    test_memory_kb, test_seconds);
  EXPECT_EQ(o.exit_code, 1) << o.output;
  const json r = read_json(dir_ / "out" / "study.json");
  ASSERT_EQ(r["cases"].size(), 2u);
  EXPECT_EQ(r["cases"][0]["status"], "bad-input");
  EXPECT_EQ(r["cases"][0]["message"], "sweep[1].path: \"/loads\" is an empty list: 0 is past its end");
  EXPECT_EQ(r["cases"][1]["status"], "converged");
}

TEST_F(Study, ARangeNearTheLimitsOfWholeNumbersIsRefused) {
  // 2⁶³ − 7 + 5 overflows a long: the values were counted on past it, allocating without end.
  expect_refused(study(R"([{"name": "n", "path": "/members/0/divisions", "range": [9223372036854775800, 9223372036854775807, 5]}])"),
                 "sweep[0].range[0]: must be between -9007199254740992 and 9007199254740992, got 9223372036854775800");
  // to − from = 2⁶⁴ − 1 overflows a long.
  expect_refused(study(R"([{"name": "n", "path": "/members/0/divisions", "range": [-9223372036854775808, 9223372036854775807, 4611686018427387904]}])"),
                 "sweep[0].range[0]: must be between -9007199254740992 and 9007199254740992, got -9223372036854775808");
  expect_refused(study(R"([{"name": "n", "path": "/members/0/divisions", "range": [1, 18446744073709551615]}])"),
                 "sweep[0].range[1]: must be between -9007199254740992 and 9007199254740992, got 18446744073709551615");
  // Within ±2⁵³ a large step is counted without overflow: [1, 2⁵³] in steps of 2⁶³ − 1 is one
  // value (1 + 2⁶³ − 1 overflows a long).
  json s = study(R"([{"name": "e", "path": "/extra", "range": [1, 9007199254740992, 9223372036854775807]}])");
  const Outcome o = run_cli_bounded("study " + write("study.json", s) + " --out " + (dir_ / "out").string() + " -q",
                                    test_memory_kb, test_seconds);
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_EQ(read_json(dir_ / "out" / "study.json")["cases"].size(), 1u);
}

TEST_F(Study, ASweepOfMoreThanAMillionCasesIsRefusedEvenWhenTheCountWouldWrapToZero) {
  // 4 parameters of 65,536 values: 2⁶⁴ cases, which a 64-bit product wraps to 0.
  const char* four = R"([{"name": "a", "path": "/extra/a", "range": [1, 65536]}, {"name": "b", "path": "/extra/b", "range": [1, 65536]},
                         {"name": "c", "path": "/extra/c", "range": [1, 65536]}, {"name": "d", "path": "/extra/d", "range": [1, 65536]}])";
  json s = study(four);
  s["model"]["extra"] = json::object();
  expect_refused(s, "sweep: more than a million cases (1.84e+19)");
  // 1,001 × 1,000 = 1,001,000: just past the limit, counted exactly.
  s = study(R"([{"name": "a", "path": "/extra/a", "range": [1, 1001]}, {"name": "b", "path": "/extra/b", "range": [1, 1000]}])");
  s["model"]["extra"] = json::object();
  expect_refused(s, "sweep: more than a million cases (1001000)");
}

TEST_F(Study, ACaseBeyondItsShareOfMemoryIsARowNotAnAbort) {
  // 10⁷ elements do not fit in 600 MB: the case is refused before its memory is spent, with its
  // estimate against its share of what ulimit -v leaves (two jobs) — its row's message; the other
  // case converges. (Its std::bad_alloc on a worker thread once ended the program, then became
  // the row after the memory had run out.)
  if (tsm::test::address_sanitizer) GTEST_SKIP() << "under AddressSanitizer the bound is on resident memory, not ulimit -v, the limit this test names";
  json s = study(R"([{"name": "divisions", "path": "/members/0/divisions", "values": [2, 10000000]}])");
  const Outcome o = run_cli_bounded("study " + write("study.json", s) + " --out " + (dir_ / "out").string() + " -q --jobs 2",
                                    600'000, test_seconds);
  EXPECT_EQ(o.exit_code, 1) << o.output;
  const json r = read_json(dir_ / "out" / "study.json");
  ASSERT_EQ(r["cases"].size(), 2u);
  EXPECT_EQ(r["cases"][0]["status"], "converged");
  EXPECT_EQ(r["cases"][1]["status"], "bad-input");
  const std::string message = r["cases"][1]["message"];
  EXPECT_EQ(message.rfind("members: the run needs ~5.6 GB of memory (10,000,000 elements and 10,000,001 nodes 4.8 GB,", 0), 0u) << message;
  EXPECT_NE(message.find("left by the address-space limit (ulimit -v) among 2 study jobs"), std::string::npos) << message;
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
      EXPECT_TRUE(c["converged"].get<bool>()) << setup << " n = " << c["divisions"].get<int>();
    }
    if (setup.find("L/h=100") != std::string::npos && element == "euler-bernoulli" && !c["converged"].get<bool>() &&
        c["divisions"].get<int>() <= 200)
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

/// A study of `cases` cases of a 400-element cantilever rolled up in 3,000 load steps each (a few
/// tenths of a second a case), its cases' results kept.
json slow_study(int cases) {
  json m = json::parse(R"({
    "materials": {"steel": {"E": 2.05e11, "G": 7.9e10}},
    "sections": {"s": {"A": 0.01, "I": 8.333333333333335e-06, "shear_area": 0.008333333333333335}},
    "nodes": [{"id": 1, "x": 0.0, "y": 0.0}, {"id": 2, "x": 10.0, "y": 0.0}],
    "members": [{"from": 1, "to": 2, "divisions": 400, "element": "timoshenko", "material": "steel", "section": "s"}],
    "supports": [{"node": 1, "type": "fixed"}],
    "loads": [{"node": 2, "mz": 1073377.489976513}],
    "analysis": {"control": {"type": "load", "steps": 3000}, "output": "last"}})");
  json steps = json::array();
  for (int k = 0; k < cases; ++k) steps.push_back(3000 + k);
  return {{"model", m}, {"keep", true}, {"sweep", json::array({{{"name", "load_steps"}, {"path", "/analysis/control/steps"}, {"values", steps}}})}};
}

TEST_F(Study, CtrlCStartsNoNewCaseAndWritesTheRowsOfTheCasesRun) {
  const fs::path out = dir_ / "out";
  const Outcome o = run_command("timeout --preserve-status -s INT 1.5 " + std::string(TSMFRAME_CLI) + " study " +
                                write("study.json", slow_study(40)) + " -q --jobs 1 --out " + out.string() + " 2>&1");
  EXPECT_EQ(o.exit_code, 1) << o.output;
  const json r = read_json(out / "study.json");
  const size_t rows = r["cases"].size();
  EXPECT_GT(rows, 0u);
  EXPECT_LT(rows, 40u);
  EXPECT_NE(o.output.find("SIGINT: interrupted after " + std::to_string(rows) + " of 40 cases"), std::string::npos) << o.output;
  for (size_t k = 0; k < rows; ++k) {  // the cases run, in order: converged, or stopped at a step (the last one)
    EXPECT_EQ(r["cases"][k]["case"], k + 1);
    const std::string status = r["cases"][k]["status"];
    EXPECT_TRUE(status == "converged" || (k + 1 == rows && status == "interrupted")) << k << ": " << status;
    EXPECT_TRUE(fs::exists(out / "cases" / std::to_string(k + 1) / "results.json"));
  }
  std::ifstream csv(out / "study.csv");
  size_t lines = 0;
  for (std::string line; std::getline(csv, line);) ++lines;
  EXPECT_EQ(lines, rows + 1);
  for (const auto& entry : fs::directory_iterator(dir_))
    EXPECT_EQ(entry.path().filename().string().find(".tsmframe-"), std::string::npos) << "temporary left: " << entry.path();
}

/// study.json's rows without their timing: what a resumed study must give as the whole one did.
json rows_but_seconds(const json& study) {
  json rows = study["cases"];
  for (json& row : rows) row.erase("seconds");
  return rows;
}

TEST_F(Study, AStudyKilledMidWayKeepsItsFinishedRowsAndResumeRunsOnlyTheOthers) {
  // SIGKILL (no clean-up at all) once the journal holds 3 rows; --resume goes on from the dead
  // run's temporary directory: the rows and kept cases of the whole run, no case run twice.
  const std::string file = write("study.json", slow_study(8));
  const fs::path whole = dir_ / "whole", out = dir_ / "out";
  ASSERT_EQ(run_cli("study " + file + " -q --jobs 1 --out " + whole.string()).exit_code, 0);
  const std::string journal = (dir_ / ".out.tsmframe-*" / "study.rows.jsonl").string();
  const Outcome killed = run_command(std::string(TSMFRAME_CLI) + " study " + file + " -q --jobs 1 --out " + out.string() +
                                    " & p=$!; for i in $(seq 600); do [ \"$(cat " + journal +
                                    " 2>/dev/null | wc -l)\" -ge 4 ] && break; sleep 0.05; done; kill -9 $p; wait $p 2>/dev/null");
  EXPECT_EQ(killed.exit_code, 128 + 9) << killed.output;
  ASSERT_FALSE(fs::exists(out)) << "nothing committed";
  const Outcome resumed = run_cli("study " + file + " --jobs 1 --resume --out " + out.string());
  EXPECT_EQ(resumed.exit_code, 0) << resumed.output;
  const size_t at = resumed.output.find("resuming: ");
  ASSERT_NE(at, std::string::npos) << resumed.output;
  const int done = std::stoi(resumed.output.substr(at + 10));
  EXPECT_GE(done, 3) << resumed.output;
  EXPECT_LT(done, 8) << resumed.output;
  for (int k = 1; k <= 8; ++k)  // run again: only the cases not done
    EXPECT_EQ(resumed.output.find("case " + std::to_string(k) + "/8 ") != std::string::npos, k > done) << k << '\n' << resumed.output;
  EXPECT_EQ(rows_but_seconds(read_json(out / "study.json")), rows_but_seconds(read_json(whole / "study.json")));
  for (int k = 1; k <= 8; ++k) EXPECT_TRUE(fs::exists(out / "cases" / std::to_string(k) / "results.json")) << k;
  for (const auto& entry : fs::directory_iterator(dir_))
    EXPECT_EQ(entry.path().filename().string().find(".tsmframe-"), std::string::npos) << "temporary left: " << entry.path();
}

TEST_F(Study, AStudyStoppedByCtrlCResumesFromItsOutputsAndAnotherStudysRowsAreRefused) {
  const std::string file = write("study.json", slow_study(6));
  const fs::path out = dir_ / "out";
  run_command("timeout --preserve-status -s INT 1.0 " + std::string(TSMFRAME_CLI) + " study " + file + " -q --jobs 1 --out " + out.string() + " 2>&1");
  const size_t stopped = read_json(out / "study.json")["cases"].size();
  ASSERT_LT(stopped, 6u);
  // Changed since: refused, one line, the outputs as they were.
  json changed = slow_study(6);
  changed["model"]["loads"][0]["mz"] = 1e6;
  const std::string other = write("other.json", changed);
  const Outcome refused = run_cli("study " + other + " -q --resume --out " + out.string());
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_EQ(refused.output.rfind(other + ": --resume: " + (out / "study.rows.jsonl").string() + ": holds the rows of another study", 0), 0u)
      << refused.output;
  EXPECT_EQ(std::count(refused.output.begin(), refused.output.end(), '\n'), 1) << refused.output;
  EXPECT_EQ(read_json(out / "study.json")["cases"].size(), stopped);
  const Outcome resumed = run_cli("study " + file + " -q --jobs 1 --resume --out " + out.string());
  EXPECT_EQ(resumed.exit_code, 0) << resumed.output;
  const json rows = read_json(out / "study.json")["cases"];
  ASSERT_EQ(rows.size(), 6u);
  for (size_t k = 0; k < 6; ++k) {
    EXPECT_EQ(rows[k]["case"], k + 1);
    EXPECT_EQ(rows[k]["status"], "converged") << "the stopped case ran again";
    EXPECT_TRUE(fs::exists(out / "cases" / std::to_string(k + 1) / "results.json")) << k;
  }
}

TEST_F(Study, ShardsOfAStudyMergeIntoTheWholeStudyRowForRow) {
  // 7 cases in 3 shards (cases 1, 4, 7 | 2, 5 | 3, 6): merged, the whole study's rows and kept
  // cases; a shard missing is said and exit 1; a shard of another study or no shard, exit 2.
  json s = study(R"([{"name": "n", "path": "/members/0/divisions", "values": [2, 3, 4, 5, 6, 7, 8]}])");
  s["keep"] = true;
  const std::string file = write("study.json", s);
  ASSERT_EQ(run_cli("study " + file + " -q --out " + (dir_ / "whole").string()).exit_code, 0);
  std::string shards;
  const std::vector<std::vector<int>> held = {{1, 4, 7}, {2, 5}, {3, 6}};
  for (int i = 1; i <= 3; ++i) {
    const fs::path shard = dir_ / ("shard" + std::to_string(i));
    const Outcome o = run_cli("study " + file + " -q --shard " + std::to_string(i) + "/3 --out " + shard.string());
    ASSERT_EQ(o.exit_code, 0) << o.output;
    std::vector<int> cases;
    const json rows = read_json(shard / "study.json");
    for (const json& row : rows["cases"]) cases.push_back(row["case"]);
    EXPECT_EQ(cases, held[i - 1]) << i;
    shards += " " + shard.string();
  }
  const fs::path merged = dir_ / "merged";
  const Outcome o = run_cli("study-merge " + file + shards + " --out " + merged.string());
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("merged 7 of 7 cases from 3 directories"), std::string::npos) << o.output;
  EXPECT_EQ(rows_but_seconds(read_json(merged / "study.json")), rows_but_seconds(read_json(dir_ / "whole" / "study.json")));
  for (int k = 1; k <= 7; ++k) EXPECT_TRUE(fs::exists(merged / "cases" / std::to_string(k) / "results.json")) << k;
  const Outcome partial = run_cli("study-merge " + file + " " + (dir_ / "shard1").string() + " " + (dir_ / "shard3").string() +
                                  " --out " + (dir_ / "partial").string());
  EXPECT_EQ(partial.exit_code, 1) << partial.output;
  EXPECT_NE(partial.output.find("merged 5 of 7 cases from 2 directories; 2 cases missing (the first: case 2"), std::string::npos)
      << partial.output;
  json other = s;
  other["model"]["loads"][0]["fy"] = 2.0;
  const std::string other_file = write("other.json", other);
  const Outcome refused = run_cli("study-merge " + other_file + shards + " --out " + (dir_ / "refused").string());
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_EQ(refused.output.rfind(other_file + ": " + (dir_ / "shard1" / "study.rows.jsonl").string() + ": holds the rows of another study", 0), 0u)
      << refused.output;
  EXPECT_FALSE(fs::exists(dir_ / "refused"));
  const Outcome none = run_cli("study-merge " + file + " " + dir_.string() + " --out " + (dir_ / "refused").string());
  EXPECT_EQ(none.exit_code, 2) << none.output;
  EXPECT_NE(none.output.find("holds no study.rows.jsonl"), std::string::npos) << none.output;
  for (const char* bad : {"0/3", "4/3", "1/0", "1/x", "2", "-1/3"}) {
    const Outcome o = run_cli("study " + file + " -q --shard " + bad + " --out " + (dir_ / "refused").string());
    EXPECT_EQ(o.exit_code, 2) << bad << ": " << o.output;
    EXPECT_NE(o.output.find("--shard: expected I/N"), std::string::npos) << bad << ": " << o.output;
  }
  EXPECT_FALSE(fs::exists(dir_ / "refused"));
}

TEST_F(Study, TheSlurmArrayExampleRunsItsShareAndTheMergeIsTheWholeStudy) {
  // examples/cluster/study-array.sbatch as two array tasks would run it (Slurm's variables set
  // by hand, tsmframe on PATH), in the scratch directory; then the merge its comment gives.
  const std::string file = write("study.json", study(R"([{"name": "n", "path": "/members/0/divisions", "values": [2, 3, 4, 5, 6]}])"));
  const std::string path = "PATH=" + fs::path(TSMFRAME_CLI).parent_path().string() + ":$PATH";
  const std::string script = std::string(TSMFRAME_SOURCE_DIR) + "/examples/cluster/study-array.sbatch";
  for (int task = 1; task <= 2; ++task) {
    const Outcome o = run_command("cd " + dir_.string() + " && " + path + " SLURM_ARRAY_TASK_ID=" + std::to_string(task) +
                                  " SLURM_ARRAY_TASK_COUNT=2 SLURM_CPUS_PER_TASK=1 bash " + script + " " + file + " 2>&1");
    ASSERT_EQ(o.exit_code, 0) << o.output;
  }
  ASSERT_EQ(run_cli("study " + file + " -q --out " + (dir_ / "whole").string()).exit_code, 0);
  const Outcome merged = run_command("cd " + dir_.string() + " && " + path + " tsmframe study-merge " + file + " shards/* --out out-study 2>&1");
  EXPECT_EQ(merged.exit_code, 0) << merged.output;
  EXPECT_EQ(rows_but_seconds(read_json(dir_ / "out-study" / "study.json")), rows_but_seconds(read_json(dir_ / "whole" / "study.json")));
}

TEST_F(Study, ACaseWhoseResultsCannotBeKeptEndsTheStudyWithExitThree) {
  // The size limit (RLIMIT_FSIZE) below a kept case's results.json: the system fails us, no
  // case's fault — exit 3 with the OS's reason, not a row, and no output directory.
  const Outcome o = run_command("prlimit --fsize=20000 " + std::string(TSMFRAME_CLI) + " study " +
                                write("study.json", slow_study(2)) + " -q --jobs 1 --out " + (dir_ / "out").string() + " 2>&1");
  EXPECT_EQ(o.exit_code, 3) << o.output;
  EXPECT_NE(o.output.find("File too large\n"), std::string::npos) << o.output;
  EXPECT_EQ(std::count(o.output.begin(), o.output.end(), '\n'), 1) << o.output;
  EXPECT_FALSE(fs::exists(dir_ / "out"));
  for (const auto& entry : fs::directory_iterator(dir_))
    EXPECT_EQ(entry.path().filename().string().find(".tsmframe-"), std::string::npos) << "temporary left: " << entry.path();
}

}  // namespace
