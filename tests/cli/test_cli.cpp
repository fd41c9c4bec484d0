// The command line as a user meets it: exit codes 0 / 1 / 2, one-line errors naming the file,
// the JSON path and the reason, and nothing written for bad input.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "support/cli.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

using tsm::test::Outcome;
using tsm::test::run_cli;

/// The words after `label` on each line of `output` that starts with it, line by line.
std::vector<std::vector<std::string>> logged(const std::string& output, const std::string& label) {
  std::vector<std::vector<std::string>> lines;
  std::istringstream in(output);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind(label, 0) != 0) continue;
    std::istringstream words(line.substr(label.size()));
    lines.emplace_back();
    for (std::string word; words >> word;) lines.back().push_back(word);
  }
  return lines;
}

class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("tsmframe-cli-" + std::to_string(::getpid()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& text) {
    const fs::path path = dir_ / name;
    std::ofstream(path) << text;
    return path.string();
  }

  /// A valid cantilever with a tip load: the base every bad-input case mutates.
  static json cantilever() {
    return json::parse(R"({
      "format": "tsmframe-model/1",
      "materials": {"steel": {"E": 2.0e11, "G": 8.0e10}},
      "sections": {"box": {"A": 1.0e-2, "I": 1.0e-4, "shear_area": 8.0e-3}},
      "nodes": [{"id": 1, "x": 0.0, "y": 0.0}, {"id": 2, "x": 4.0, "y": 0.0}],
      "members": [{"from": 1, "to": 2, "divisions": 4, "element": "timoshenko", "material": "steel", "section": "box"}],
      "supports": [{"node": 1, "type": "fixed"}],
      "loads": [{"node": 2, "fy": 1.0e5}],
      "analysis": {"control": {"type": "load", "steps": 2}}
    })");
  }

  fs::path dir_;
};

TEST_F(Cli, ConvergedRunWritesBothFilesAndExitsZero) {
  const std::string model = write("ok.json", cantilever().dump());
  const Outcome o = run_cli("run " + model + " --out " + (dir_ / "out").string());
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("step 2"), std::string::npos) << o.output;  // progress lines
  const json results = json::parse(std::ifstream(dir_ / "out" / "results.json"));
  EXPECT_EQ(results["format"], "tsmframe-results/1");
  EXPECT_EQ(results["status"], "converged");
  ASSERT_EQ(results["steps"].size(), 2u);
  EXPECT_EQ(results["steps"][1]["load_factor"], 1.0);
  EXPECT_EQ(results["nodes"].size(), 5u);
  EXPECT_EQ(results["elements"][0]["nodes"], json::array({1, 3}));  // generated nodes continue the ids
  EXPECT_EQ(results["steps"][1]["displacements"]["2"].size(), 3u);
  EXPECT_EQ(results["steps"][1]["reactions"].size(), 1u);  // only the supported node
  EXPECT_TRUE(fs::exists(dir_ / "out" / "steps.csv"));
  for (const auto& entry : fs::directory_iterator(dir_ / "out"))
    EXPECT_EQ(entry.path().string().find(".tmp-"), std::string::npos) << "temporary left: " << entry.path();
}

TEST_F(Cli, ARunGoesOnFromAKeptStepOfAnEarlierRun) {
  json m = cantilever();
  m["analysis"]["control"]["steps"] = 4;
  const std::string model = write("ok.json", m.dump());
  const std::string whole = (dir_ / "whole").string(), rest = (dir_ / "rest").string();
  ASSERT_EQ(run_cli("run " + model + " -q --out " + whole).exit_code, 0);
  const Outcome o = run_cli("run " + model + " --from " + whole + "/results.json#2 --out " + rest);
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("step 3 "), std::string::npos) << o.output;  // numbered on
  EXPECT_EQ(o.output.find("step 1 "), std::string::npos) << o.output;
  const json a = json::parse(std::ifstream(fs::path(whole) / "results.json"));
  const json b = json::parse(std::ifstream(fs::path(rest) / "results.json"));
  ASSERT_EQ(b["steps"].size(), 2u);
  EXPECT_EQ(b["steps"][0]["step"], 3);
  EXPECT_EQ(b["steps"][1]["displacements"], a["steps"][3]["displacements"]);  // the same, bit for bit
  // What cannot be gone on from: one line naming the results file, exit 2, nothing written.
  for (const auto& [from, reason] : std::vector<std::pair<std::string, std::string>>{
           {whole + "/results.json#9", "steps: no step 9 in these results"},
           {whole + "/results.json#two", "#two: expected a step number"},
           {whole + "/nothing.json", "cannot open"},
           {model, "format: not a tsmframe results file"}}) {
    const Outcome bad = run_cli("run " + model + " --from " + from + " --out " + (dir_ / "bad").string());
    EXPECT_EQ(bad.exit_code, 2) << from << ": " << bad.output;
    EXPECT_EQ(bad.output.rfind(from.substr(0, from.find('#')), 0), 0u) << bad.output;
    EXPECT_NE(bad.output.find(reason), std::string::npos) << bad.output;
    EXPECT_EQ(std::count(bad.output.begin(), bad.output.end(), '\n'), 1) << bad.output;
    EXPECT_FALSE(fs::exists(dir_ / "bad"));
  }
}

TEST_F(Cli, QuietRunPrintsNothing) {
  const std::string model = write("ok.json", cantilever().dump());
  const Outcome o = run_cli("run " + model + " --quiet --out " + (dir_ / "out").string());
  EXPECT_EQ(o.exit_code, 0);
  EXPECT_EQ(o.output, "");
}

TEST_F(Cli, HelpAndVersion) {
  EXPECT_EQ(run_cli("--help").exit_code, 0);
  const Outcome v = run_cli("--version");
  EXPECT_EQ(v.exit_code, 0);
  EXPECT_NE(v.output.find("tsmframe"), std::string::npos);
}

TEST_F(Cli, UsageErrorsExitTwo) {
  EXPECT_EQ(run_cli("").exit_code, 2);
  EXPECT_EQ(run_cli("run").exit_code, 2);
  EXPECT_EQ(run_cli("fly model.json").exit_code, 2);
  EXPECT_EQ(run_cli("run a.json --no-such-option").exit_code, 2);
  const Outcome missing = run_cli("run " + (dir_ / "missing.json").string());
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.output.find("cannot open"), std::string::npos) << missing.output;
}

TEST_F(Cli, NonConvergenceExitsOneAndKeepsConvergedSteps) {
  // A load far beyond what 1 iteration per step can carry, without cutback: step 1 converges
  // (linear-ish at 1e-6 of the load), step 2 jumps to the full load and fails.
  json m = cantilever();
  m["loads"][0]["fy"] = 1e9;
  m["analysis"] = {{"control", {{"type", "load"}, {"steps", 2}}}, {"max_iterations", 3}, {"cutback", false}};
  m["loads"] = json::array({{{"node", 2}, {"fy", 1e9}}});
  const std::string model = write("hard.json", m.dump());
  const Outcome o = run_cli("run " + model + " --out " + (dir_ / "out").string());
  EXPECT_EQ(o.exit_code, 1) << o.output;
  EXPECT_NE(o.output.find("did not converge"), std::string::npos) << o.output;
  const json results = json::parse(std::ifstream(dir_ / "out" / "results.json"));
  EXPECT_NE(results["status"], "converged");
  EXPECT_FALSE(results["message"].get<std::string>().empty());
  const json& last = results["steps"].back();
  EXPECT_FALSE(last["converged"].get<bool>());
  EXPECT_FALSE(last.contains("displacements"));
  EXPECT_EQ(results.dump().find("NaN"), std::string::npos);
}

struct BadCase {
  const char* name;
  std::function<void(json&)> mutate;
  const char* expected;  // substring of the one-line message (path and reason)
};

TEST_F(Cli, BadInputNamesFilePathAndReason) {
  const std::vector<BadCase> cases = {
      {"unknown key", [](json& m) { m["members"][0]["sectoin"] = "box"; }, "members[0].sectoin: unknown key"},
      {"missing E", [](json& m) { m["materials"]["steel"].erase("E"); }, "materials.steel.E: missing"},
      {"zero E", [](json& m) { m["materials"]["steel"]["E"] = 0; }, "materials.steel.E: must be positive"},
      {"negative A", [](json& m) { m["sections"]["box"]["A"] = -1; }, "sections.box.A: must be positive"},
      {"missing I", [](json& m) { m["sections"]["box"].erase("I"); }, "sections.box.I: missing"},
      {"no G for Timoshenko", [](json& m) { m["materials"]["steel"].erase("G"); }, "members[0].material: material \"steel\" has no G"},
      {"no shear area", [](json& m) { m["sections"]["box"].erase("shear_area"); }, "members[0].section: section \"box\" has no shear_area"},
      {"unknown material", [](json& m) { m["members"][0]["material"] = "stel"; }, "members[0].material: unknown material \"stel\""},
      {"unknown section", [](json& m) { m["members"][0]["section"] = "bx"; }, "members[0].section: unknown section \"bx\""},
      {"unknown node", [](json& m) { m["members"][0]["to"] = 7; }, "members[0].to: unknown node 7"},
      {"duplicate id", [](json& m) { m["nodes"][1]["id"] = 1; }, "nodes[1].id: duplicate node id 1"},
      {"zero length", [](json& m) { m["members"][0]["to"] = 1; }, "members[0]: zero-length member"},
      {"empty member load", [](json& m) { m["members"][0]["load"] = json::object(); }, "members[0].load: give fx, fy or pressure"},
      {"member load typo", [](json& m) { m["members"][0]["load"] = {{"fz", 1.0}}; }, "members[0].load.fz: unknown key"},
      {"unknown release", [](json& m) { m["members"][0]["release"] = "top"; }, "members[0].release: unknown release \"top\""},
      {"no node at point", [](json& m) { m["loads"][0]["node"] = json::array({4.5, 0.0}); }, "loads[0].node: no node at [4.5, 0] (the nearest, node 2, is at [4, 0], 0.5 away)"},
      {"several nodes at point",
       [](json& m) {
         m["nodes"].push_back({{"id", 9}, {"x", 4.0}, {"y", 0.0}});
         m["loads"][0]["node"] = json::array({4.0, 0.0});
       },
       "loads[0].node: 2 nodes at [4, 0]"},
      {"arc sweep that misses the end node",  // nodes (0, 0), (4, 0) on a circle about (2, 2): π/2 or −3π/2 reaches
       [](json& m) { m["members"][0]["arc"] = {{"center", {2.0, 2.0}}, {"sweep", 1.0}}; },
       "members[0].arc.sweep: the sweep from the start node does not end at the end node (1.5707963267948966 or "
       "-4.71238898038469 does)"},
      {"mechanism", [](json& m) { m["supports"][0]["type"] = "pinned"; }, "supports: structure is a mechanism"},
      {"free node", [](json& m) { m["nodes"].push_back({{"id", 5}, {"x", 1.0}, {"y", 1.0}}); }, "supports: structure is a mechanism: node 5 is held by no element"},
      {"beam on a knife edge drawn on its axis",
       [](json& m) {
         m["nodes"].push_back({{"id", 5}, {"x", 3.0}, {"y", 0.0}});
         m["supports"] = json::array({{{"node", 1}, {"type", "pinned"}}, {{"node", 5}, {"type", "fixed"}}});
         m["contacts"] = json::array({{{"node", 5}, {"members", "all"}}});
       },
       "supports: structure is a mechanism: the part holding node 1 and the 4 nodes joined to it is free to rotate about (0, 0) "
       "(add a support that stops it); a contact holds it from the start only if its node is drawn at the contact's "
       "\"gap\" from the beam's centre line, on the side it supports, and the node or the beam is held (by supports, or "
       "by a part that is) (contact node 5 lies on the centre line itself with gap 0, so it rests on neither side"},
      {"block drawn above a beam, its gap 0 (dropped onto it)",
       [](json& m) {
         m["nodes"].push_back({{"id", 5}, {"x", 2.5}, {"y", 0.02}});
         m["nodes"].push_back({{"id", 6}, {"x", 3.5}, {"y", 0.02}});
         m["members"].push_back({{"from", 5}, {"to", 6}, {"material", m["members"][0]["material"]}, {"section", m["members"][0]["section"]}});
         m["supports"].push_back({{"node", 5}, {"fix", {"ux"}}});
         m["contacts"] = json::array({{{"node", 5}, {"members", {0}}}, {{"node", 6}, {"members", {0}}}});
       },
       "supports: structure is a mechanism: the part holding node 5 and the 1 node joined to it is free to move along y "
       "(no support fixes uy); a contact holds it from the start only if its node is drawn at the contact's \"gap\" from "
       "the beam's centre line, on the side it supports, and the node or the beam is held (by supports, or by a part that "
       "is) (contact node 5 is drawn 0.02 from the beam's centre line, its gap is 0: a part that only contacts would hold "
       "cannot fall onto them in a static analysis"},
      {"two contacts resting on one element in different frames",
       [](json& m) {
         m["nodes"].push_back({{"id", 5}, {"x", 2.2}, {"y", -0.05}});
         m["nodes"].push_back({{"id", 6}, {"x", 2.8}, {"y", -0.05}});
         m["supports"].push_back({{"node", 5}, {"type", "fixed"}});
         m["supports"].push_back({{"node", 6}, {"type", "fixed"}});
         m["contacts"] = json::array({{{"node", 5}, {"members", "all"}, {"gap", 0.05}},
                                      {{"node", 6}, {"members", "all"}, {"gap", 0.05}, {"frame", "cantilever"}}});
       },
       "contacts[1]: rests on element 3, as contacts[0] does in the other frame: points on one element share its frame "
       "(give both the same \"frame\")"},
      {"unknown normal",
       [](json& m) {
         m["nodes"].push_back({{"id", 3}, {"x", 2.0}, {"y", 1.0}});
         m["supports"].push_back({{"node", 3}, {"type", "fixed"}});
         m["contacts"] = json::array({{{"node", 3}, {"members", {0}}, {"normal", "bent"}}});
       },
       "contacts[0].normal: unknown normal \"bent\" (expected \"chord\" or \"deflected\")"},
      {"load on missing node", [](json& m) { m["loads"][0]["node"] = 42; }, "loads[0].node: unknown node 42"},
      {"contact on missing node",
       [](json& m) { m["contacts"] = json::array({{{"node", 42}, {"members", "all"}}}); },
       "contacts[0].node: unknown node 42"},
      {"contact on missing member",
       [](json& m) {
         m["nodes"].push_back({{"id", 5}, {"x", 1.0}, {"y", -0.1}});
         m["supports"].push_back({{"node", 5}, {"type", "fixed"}});
         m["contacts"] = json::array({{{"node", 5}, {"members", {3}}}});
       },
       "contacts[0].members[0]: unknown member 3"},
      {"contact edge out of range",
       [](json& m) {
         m["nodes"].push_back({{"id", 5}, {"x", 1.0}, {"y", -0.1}});
         m["supports"].push_back({{"node", 5}, {"type", "fixed"}});
         m["contacts"] = json::array({{{"node", 5}, {"members", "all"}, {"edge", 0.5}}});
       },
       "contacts[0].edge: must lie between 1e-12 and 0.25"},
      {"contact stiffness ratio below 1",
       [](json& m) {
         m["nodes"].push_back({{"id", 5}, {"x", 1.0}, {"y", -0.1}});
         m["supports"].push_back({{"node", 5}, {"type", "fixed"}});
         m["contacts"] = json::array({{{"node", 5}, {"members", "all"}, {"max_stiffness_ratio", 0.5}}});
       },
       "contacts[0].max_stiffness_ratio: must be at least 1"},
      {"negative friction",
       [](json& m) {
         m["nodes"].push_back({{"id", 5}, {"x", 1.0}, {"y", -0.1}});
         m["supports"].push_back({{"node", 5}, {"type", "fixed"}});
         m["contacts"] = json::array({{{"node", 5}, {"members", "all"}, {"friction", -0.2}}});
       },
       "contacts[0].friction: must lie between 0 and 10"},
      {"friction as text",
       [](json& m) {
         m["nodes"].push_back({{"id", 5}, {"x", 1.0}, {"y", -0.1}});
         m["supports"].push_back({{"node", 5}, {"type", "fixed"}});
         m["contacts"] = json::array({{{"node", 5}, {"members", "all"}, {"friction", "0.3"}}});
       },
       "contacts[0].friction: "},
      {"friction in the cantilever frame",
       [](json& m) {
         m["nodes"].push_back({{"id", 5}, {"x", 1.0}, {"y", -0.1}});
         m["supports"].push_back({{"node", 5}, {"type", "fixed"}});
         m["contacts"] = json::array({{{"node", 5}, {"members", "all"}, {"frame", "cantilever"}, {"friction", 0.3}}});
       },
       "contacts[0].friction: friction is not in the cantilever frame yet"},
      {"a free contact node drawn off its gap",  // only its uy free, 0.1 above the beam, gap 0.05
       [](json& m) {
         m["nodes"].push_back({{"id", 5}, {"x", 1.5}, {"y", 0.1}});
         m["supports"].push_back({{"node", 5}, {"fix", {"ux", "rz"}}});
         m["contacts"] = json::array({{{"node", 5}, {"members", "all"}, {"gap", 0.05}}});
       },
       "supports: structure is a mechanism: node 5 is held by no element and its uy is not supported (a contact node is "
       "held by its contact only if drawn at its \"gap\" from the beam and free in one direction only, across the beam: "
       "else prescribe its motion, or make it a node of a beam) (contact node 5 is drawn 0.1 from the beam's centre line, "
       "its gap is 0.05"},
      {"contact node twice",
       [](json& m) {
         m["nodes"].push_back({{"id", 5}, {"x", 1.0}, {"y", -0.1}});
         m["supports"].push_back({{"node", 5}, {"type", "fixed"}});
         m["contacts"] = json::array({{{"node", 5}, {"members", "all"}}, {{"node", 5}, {"members", {0}}}});
       },
       "contacts[1].node: this node already has a contact entry"},
      {"contact node and nodes both",
       [](json& m) {
         m["nodes"].push_back({{"id", 5}, {"x", 1.0}, {"y", -0.1}});
         m["supports"].push_back({{"node", 5}, {"type", "fixed"}});
         m["contacts"] = json::array({{{"node", 5}, {"nodes", {5}}, {"members", "all"}}});
       },
       "contacts[0].nodes: give either node or nodes, not both"},
      {"contact nodes of a missing member",
       [](json& m) { m["contacts"] = json::array({{{"nodes", {{"members", {4}}}}, {"members", "all"}}}); },
       "contacts[0].nodes.members[0]: unknown member 4"},
      {"contact nodes: one of them on a member it touches",
       [](json& m) {
         m["nodes"].push_back({{"id", 5}, {"x", 1.0}, {"y", -0.1}});
         m["supports"].push_back({{"node", 5}, {"type", "fixed"}});
         m["contacts"] = json::array({{{"nodes", {5, 2}}, {"members", {0}}}});
       },
       "contacts[0].members[0]: the contact node 2 belongs to member 0"},
      {"contact nodes: one listed twice",
       [](json& m) {
         m["nodes"].push_back({{"id", 5}, {"x", 1.0}, {"y", -0.1}});
         m["supports"].push_back({{"node", 5}, {"type", "fixed"}});
         m["contacts"] = json::array({{{"nodes", {5, {1.0, -0.1}}}, {"members", "all"}}});
       },
       "contacts[0].nodes[1]: node 5 already has a contact entry"},
      {"contact nodes empty", [](json& m) { m["contacts"] = json::array({{{"nodes", json::array()}, {"members", "all"}}}); },
       "contacts[0].nodes: no node listed"},
      {"every step's state kept, beyond 8 GB",
       [](json& m) {
         m["members"][0]["divisions"] = 100000;
         m["analysis"]["control"]["steps"] = 10000;
       },
       "analysis.output: keeping the full state of 10000 steps of 100000 elements takes ~80 GB of memory"},
      {"a load beyond 1e50", [](json& m) { m["loads"][0]["fy"] = -1e300; },
       "loads[0].fy: beyond ±1e50 (-1e+300): no unit system needs it"},
      {"load path standing still", [](json& m) { m["analysis"]["control"]["path"] = {1.0, 1.0}; }, "analysis.control.path[1]: repeats the load factor"},
      {"arc-length without max_steps",
       [](json& m) { m["analysis"]["control"] = {{"type", "arc-length"}, {"initial_increment", 0.1}}; },
       "analysis.control.max_steps: missing (required)"},
      {"arc-length until on a fixed dof",
       [](json& m) {
         m["analysis"]["control"] = {{"type", "arc-length"}, {"initial_increment", 0.1}, {"max_steps", 10},
                                     {"until", {{"node", 1}, {"dof", "uy"}, {"value", 1.0}}}};
       },
       "analysis.control.until.dof: the dof uy of node 1 is fixed or prescribed"},
      {"arc-length bounds",
       [](json& m) {
         m["analysis"]["control"] = {{"type", "arc-length"}, {"initial_increment", 0.1}, {"max_steps", 10}, {"min_increment", 0.2}};
       },
       "analysis.control.min_increment: must not exceed initial_increment"},
      {"bad control", [](json& m) { m["analysis"]["control"]["type"] = "force"; }, "analysis.control.type: unknown control"},
      {"bad steps", [](json& m) { m["analysis"]["control"]["steps"] = 0; }, "analysis.control.steps: must be between 1"},
      {"fractional divisions", [](json& m) { m["members"][0]["divisions"] = 2.5; }, "members[0].divisions: expected a whole number"},
      {"wrong type", [](json& m) { m["nodes"][0]["x"] = "0"; }, "nodes[0].x: expected a number, found a string"},
      {"bad dof", [](json& m) { m["supports"][0] = {{"node", 1}, {"fix", {"ux", "uz"}}}; }, "supports[0].fix[1]: unknown dof \"uz\""},
      {"controlled dof fixed",
       [](json& m) { m["analysis"]["control"] = {{"type", "displacement"}, {"node", 1}, {"dof", "uy"}, {"target", 1.0}}; },
       "analysis.control.dof: the controlled dof uy of node 1 is fixed"},
      {"bad format", [](json& m) { m["format"] = "tsmframe-model/2"; }, "format: unsupported format"},
      {"between and members",
       [](json& m) { m["contacts"] = json::array({{{"between", {{0}, {0}}}, {"members", {0}}}}); },
       "contacts[0].members: give either \"between\" or node(s) and members, not both"},
      {"between one side", [](json& m) { m["contacts"] = json::array({{{"between", {{0}}}}}); },
       "contacts[0].between: expected two lists of member indices, [[A…], [B…]]"},
      {"between unknown member", [](json& m) { m["contacts"] = json::array({{{"between", {{0}, {3}}}}}); },
       "contacts[0].between[1][0]: unknown member 3 (members are numbered 0 to 0 in file order)"},
      {"between a member and itself", [](json& m) { m["contacts"] = json::array({{{"between", {{0}, {0}}}}}); },
       "contacts[0].between: member 0 is on both sides"},
      {"contact without members", [](json& m) { m["contacts"] = json::array({{{"node", 2}}}); },
       "contacts[0].members: missing (required, or give \"between\")"},
      {"end springs with neither end", [](json& m) { m["members"][0]["end_springs"] = {{"extra", "note"}}; },
       "members[0].end_springs: give start or end"},
  };
  for (const BadCase& c : cases) {
    json m = cantilever();
    c.mutate(m);
    const std::string model = write("bad.json", m.dump(2));
    const fs::path out = dir_ / "out-bad";
    const Outcome o = run_cli("run " + model + " --out " + out.string());
    EXPECT_EQ(o.exit_code, 2) << c.name << ": " << o.output;
    EXPECT_NE(o.output.find(model + ": " + c.expected), std::string::npos) << c.name << ": " << o.output;
    EXPECT_EQ(std::count(o.output.begin(), o.output.end(), '\n'), 1) << c.name << ": " << o.output;
    EXPECT_FALSE(fs::exists(out)) << c.name << ": output written for bad input";
  }
}

TEST_F(Cli, ContactResultsInJsonAndCsv) {
  // The cantilever pushed up at x = 1.1 by a rigid node starting 15 mm below it.
  json m = cantilever();
  m["loads"] = json::array();
  m["nodes"].push_back({{"id", 100}, {"x", 1.1}, {"y", -0.015}});
  m["supports"].push_back({{"node", 100}, {"fix", {"ux"}}});
  m["prescribed"] = json::array({{{"node", 100}, {"uy", 0.05}}});
  m["contacts"] = json::array({{{"node", 100}, {"members", "all"}}});
  m["analysis"] = {{"control", {{"type", "load"}, {"steps", 5}}}};
  const std::string model = write("push.json", m.dump(2));
  const fs::path out = dir_ / "out";
  const Outcome o = run_cli("run " + model + " --out " + out.string() + " --log-iterations");
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("contact at node 100 element:alpha per iterate: 2:"), std::string::npos) << o.output;
  std::ifstream in(out / "results.json");
  const json r = json::parse(in);
  // The log's counts are the run's: per step, one entry per iterate (iterate 0 and one per
  // iteration, as the residuals), and at the last iterate the contacts in touch that results.json
  // holds for the step.
  const auto residuals = logged(o.output, "  residual per iterate:");
  const auto in_touch = logged(o.output, "  contacts in touch per iterate:");
  ASSERT_EQ(residuals.size(), r["steps"].size()) << o.output;
  ASSERT_EQ(in_touch.size(), r["steps"].size()) << o.output;
  for (size_t k = 0; k < in_touch.size(); ++k) {
    const json& step = r["steps"][k];
    EXPECT_EQ(in_touch[k].size(), step["iterations"].get<size_t>() + 1) << "step " << k + 1;
    EXPECT_EQ(residuals[k].size(), in_touch[k].size()) << "step " << k + 1;
    ASSERT_FALSE(in_touch[k].empty());
    EXPECT_EQ(in_touch[k].back(), std::to_string(step["contacts"].size())) << "step " << k + 1;
  }
  const json& last = r["steps"].back();
  ASSERT_EQ(last["contacts"].size(), 1u);
  const json& c = last["contacts"][0];
  EXPECT_EQ(c["node"], 100);
  EXPECT_EQ(c["element"], 2);  // x = 1.1 lies in element 2 (1 … 2)
  EXPECT_GT(c["xi"].get<double>(), 0.0);
  EXPECT_LT(c["xi"].get<double>(), 1.0);
  EXPECT_GT(c["force"].get<double>(), 0.0);
  ASSERT_EQ(last["element_forces"]["2"].size(), 4u);  // N, M_i, M_j, Y
  // Y is the force's part along the chord's normal: along the bent beam's normal ν = n − w'e the
  // force is Y √(1 + w'²), w' the small slope against the chord at the point.
  const double Y = last["element_forces"]["2"][3].get<double>();
  EXPECT_LE(Y, c["force"].get<double>() * (1.0 + 1e-12));
  EXPECT_GT(Y, 0.99 * c["force"].get<double>());
  EXPECT_EQ(last["element_forces"]["1"].size(), 3u);
  EXPECT_EQ(r["steps"][0]["contacts"].size(), 0u);  // the first 10 mm do not close the 15 mm gap
  std::ifstream csv(out / "steps.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_NE(header.find(",contact_element_100,contact_xi_100,contact_force_100,Ry_100"), std::string::npos) << header;
  // The pusher's prescribed uy has its reaction in every row (the force that drives the model),
  // as results.json has it; with the reaction across (its ux is held) it is the contact force,
  // normal to the tilted beam.
  std::string row_text, last_row;
  int rows = 0;
  while (std::getline(csv, row_text)) last_row = row_text, ++rows;
  EXPECT_EQ(rows, 5);
  const double Ry = std::stod(last_row.substr(last_row.rfind(',') + 1));
  const json& reaction = last["reactions"]["100"];
  EXPECT_EQ(Ry, reaction[1].get<double>()) << last_row;
  EXPECT_NEAR(std::hypot(reaction[0].get<double>(), reaction[1].get<double>()), c["force"].get<double>(),
              1e-9 * c["force"].get<double>());
  EXPECT_GT(std::abs(reaction[0].get<double>()), 1e-3 * Ry) << "the beam is tilted under the push";
}

TEST_F(Cli, ArcLengthMarksLimitPoints) {
  // A shallow two-bar truss (bending negligible) under an apex load: snap-through.
  const json m = json::parse(R"({
    "materials": {"m": {"E": 1.0}}, "sections": {"s": {"A": 1.0, "I": 1e-9}},
    "nodes": [{"id": 1, "x": 0, "y": 0}, {"id": 2, "x": 1, "y": 0.1}, {"id": 3, "x": 2, "y": 0}],
    "members": [{"from": 1, "to": 2, "material": "m", "section": "s"}, {"from": 2, "to": 3, "material": "m", "section": "s"}],
    "supports": [{"node": 1, "type": "pinned"}, {"node": 3, "type": "pinned"}],
    "loads": [{"node": 2, "fy": -1e-3}],
    "analysis": {"control": {"type": "arc-length", "initial_increment": 0.01, "max_increment": 0.01, "max_steps": 200,
                             "until": {"node": 2, "dof": "uy", "value": -0.25}}}})");
  const std::string model = write("truss.json", m.dump(2));
  const fs::path out = dir_ / "out";
  const Outcome o = run_cli("run " + model + " --out " + out.string());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("arc length 0.01"), std::string::npos) << o.output;
  std::ifstream in(out / "results.json");
  const json r = json::parse(in);
  ASSERT_EQ(r["limit_points"].size(), 2u);
  EXPECT_EQ(r["limit_points"][0]["kind"], "maximum");
  EXPECT_EQ(r["limit_points"][1]["kind"], "minimum");
  EXPECT_GT(r["limit_points"][0]["load_factor"].get<double>(), 0.0);
  EXPECT_LT(r["limit_points"][1]["load_factor"].get<double>(), 0.0);
  EXPECT_GT(r["steps"][0]["arc_length"].get<double>(), 0.0);
  // a budget too small for the `until`: exit 1, status step-limit, steps kept
  json short_run = m;
  short_run["analysis"]["control"]["max_steps"] = 3;
  const std::string model2 = write("short.json", short_run.dump(2));
  const Outcome o2 = run_cli("run " + model2 + " --out " + (dir_ / "out2").string());
  EXPECT_EQ(o2.exit_code, 1) << o2.output;
  std::ifstream in2(dir_ / "out2" / "results.json");
  const json r2 = json::parse(in2);
  EXPECT_EQ(r2["status"], "step-limit");
  EXPECT_EQ(r2["steps"].size(), 3u);
}

TEST_F(Cli, InvalidJsonNamesLineAndColumn) {
  const std::string model = write("broken.json", "{\n  \"nodes\": [\n    {\"id\": 1,, \"x\": 0}\n  ]\n}\n");
  const Outcome o = run_cli("run " + model + " --out " + (dir_ / "out").string());
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_NE(o.output.find("invalid JSON at line 3, column 14"), std::string::npos) << o.output;
  EXPECT_FALSE(fs::exists(dir_ / "out"));
  // A number beyond a double's range is bad input too (it was an "internal error", exit 1).
  json m = cantilever();
  std::string text = m.dump(2);
  text.replace(text.find("100000.0"), 8, "1e400");
  const std::string huge = write("huge.json", text);
  const Outcome h = run_cli("run " + huge + " --out " + (dir_ / "out").string());
  EXPECT_EQ(h.exit_code, 2) << h.output;
  EXPECT_NE(h.output.find(huge + ": invalid JSON: number overflow parsing '1e400' (beyond a double's range)"), std::string::npos)
      << h.output;
  EXPECT_FALSE(fs::exists(dir_ / "out"));
}

}  // namespace
