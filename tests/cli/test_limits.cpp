// The command line against inputs that would take more than a machine has, or than any sane
// model needs: each is refused up front with one line and exit 2 (past a limit every model is
// held to) or 3 (more memory than this machine has: README, "Memory"), never read without end,
// never an abort. Each runs within an address-space limit and a time limit, so that a regression
// fails its test instead of exhausting the machine.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "support/cli.hpp"
#include "support/scratch_directory.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using tsm::test::Outcome;
using tsm::test::run_cli_bounded;

constexpr long gigabyte = 1'000'000;  // ulimit -v counts kilobytes
constexpr int seconds = 20;

class Limits : public tsm::test::ScratchDirectory {
 protected:
  Limits() : ScratchDirectory("tsmframe-limits-") {}
  /// On one line: the big models stay as small as they can be.
  std::string write(const std::string& name, const json& document) { return ScratchDirectory::write(name, document, -1); }
  std::string out() const { return (dir_ / "out").string(); }
};

/// One line on stderr, and nothing written.
void expect_one_line(const Outcome& o, const std::string& line) {
  EXPECT_EQ(o.output, line + "\n");
}

TEST_F(Limits, DevZeroAsTheModelIsRefusedAtItsFirstByte) {
  // It was read until memory ran out (a NUL byte is no JSON text: nothing after it can make one).
  const Outcome o = run_cli_bounded("run /dev/zero --out " + out(), gigabyte, seconds);
  EXPECT_EQ(o.exit_code, 2) << o.output;
  expect_one_line(o, "/dev/zero: holds a NUL byte (byte 1): not JSON text");
  EXPECT_FALSE(fs::exists(out()));
  const Outcome s = run_cli_bounded("study /dev/zero --out " + out(), gigabyte, seconds);
  EXPECT_EQ(s.exit_code, 2) << s.output;
  expect_one_line(s, "/dev/zero: holds a NUL byte (byte 1): not JSON text");
}

TEST_F(Limits, ADirectoryAsTheModelIsADirectory) {
  // It was "invalid JSON at line 1, column 1: … unexpected end of input".
  const Outcome o = run_cli_bounded("run " + dir_.string() + " --out " + out(), gigabyte, seconds);
  EXPECT_EQ(o.exit_code, 2) << o.output;
  expect_one_line(o, dir_.string() + ": is a directory");
  const Outcome s = run_cli_bounded("study " + dir_.string() + " --out " + out(), gigabyte, seconds);
  EXPECT_EQ(s.exit_code, 2) << s.output;
  expect_one_line(s, dir_.string() + ": is a directory");
}

TEST_F(Limits, AModelFileBeyondOneGibibyteIsNotRead) {
  // A sparse file: its size is known without reading it (and it takes no disk).
  const fs::path huge = dir_ / "huge.json";
  std::ofstream(huge) << "{";
  fs::resize_file(huge, (1ull << 30) + 1);
  const Outcome o = run_cli_bounded("run " + huge.string() + " --out " + out(), gigabyte, seconds);
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find(huge.string() + ": larger than 1 GiB"), std::string::npos) << o.output;
}

/// A cantilever of `members` members of `divisions` elements each, end to end along x.
json members_of(int members, long divisions) {
  json m = {{"materials", {{"steel", {{"E", 2e11}}}}},
            {"sections", {{"s", {{"A", 1e-2}, {"I", 1e-4}}}}},
            {"nodes", json::array()},
            {"members", json::array()},
            {"supports", {{{"node", 0}, {"type", "fixed"}}}},
            {"loads", {{{"node", members}, {"fy", -1e3}}}}};
  for (int k = 0; k <= members; ++k) m["nodes"].push_back({{"id", k}, {"x", 10.0 * k}, {"y", 0.0}});
  for (int k = 0; k < members; ++k)
    m["members"].push_back({{"from", k}, {"to", k + 1}, {"divisions", divisions}, {"material", "steel"}, {"section", "s"}});
  return m;
}

/// A beam of `divisions` elements under `contacts` contact nodes standing pinned above it, each
/// a contact that may touch it.
json beam_under_contact_nodes(long divisions, int contacts) {
  json m = members_of(1, divisions);
  m["supports"].push_back({{"node", 1}, {"type", "roller-x"}});
  json nodes = json::array();
  for (int k = 0; k < contacts; ++k) {
    m["nodes"].push_back({{"id", 10 + k}, {"x", 10.0 * (k + 0.5) / contacts}, {"y", 1.0}});
    m["supports"].push_back({{"node", 10 + k}, {"type", "pinned"}});
    nodes.push_back(10 + k);
  }
  m["contacts"] = {{{"nodes", nodes}, {"members", "all"}}};
  return m;
}

TEST_F(Limits, TheElementCapIsCountedBeforeAnyNodeIsMade) {
  // 3 × 10⁷ divisions: the first two members were meshed (7.7 s, 3 GB) before the third passed the cap.
  const std::string model = write("three.json", members_of(3, 10'000'000));
  const Outcome o = run_cli_bounded("run " + model + " --out " + out(), gigabyte, seconds);
  EXPECT_EQ(o.exit_code, 2) << o.output;
  expect_one_line(o, model + ": members[2].divisions: the model would have more than 20000000 elements");
}

TEST_F(Limits, ContactsAreReadInTimeLinearInTheirNumber) {
  // 200,001 contact nodes: each was compared with every contact before it and every element
  // searched for the members holding it (quadratic: minutes). The analysis is refused right
  // after the contacts, so that this times the reading alone.
  json m = beam_under_contact_nodes(1, 200'001);
  m["analysis"] = {{"control", {{"type", "force"}}}};
  const std::string model = write("contacts.json", m);
  const Outcome o = run_cli_bounded("run " + model + " --out " + out(), gigabyte, seconds);
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("analysis.control.type: unknown control"), std::string::npos) << o.output;
}

/// The refusal of a run beyond the memory budget: exit 3, one line naming the file, the JSON
/// path, the estimate and the address-space limit the test runs it under.
void expect_over_budget(const Outcome& o, const std::string& model, const std::string& path_and_estimate) {
  EXPECT_EQ(o.exit_code, 3) << o.output;
  EXPECT_EQ(o.output.rfind("tsmframe: " + model + ": " + path_and_estimate, 0), 0u) << o.output;
  EXPECT_NE(o.output.find("left by the address-space limit (ulimit -v)\n"), std::string::npos) << o.output;
  EXPECT_EQ(o.output.find('\n'), o.output.size() - 1) << o.output;  // one line
}

TEST_F(Limits, TenMillionElementsAreRefusedBeforeTheyAreMadeWhereTheMachineLacksTheMemory) {
  if (tsm::test::address_sanitizer) GTEST_SKIP() << "under AddressSanitizer the bound is on resident memory, not ulimit -v";
  // 10⁷ divisions in one member (within the caps) were meshed and run until memory ran out.
  const std::string model = write("one.json", members_of(1, 10'000'000));
  const Outcome o = run_cli_bounded("run " + model + " --out " + out(), 2 * gigabyte, seconds);
  expect_over_budget(o, model, "members: the run needs ~5.6 GB of memory (10,000,000 elements and 10,000,001 nodes 4.8 GB,");
  EXPECT_FALSE(fs::exists(out()));
}

TEST_F(Limits, ContactsWhoseCandidatesWouldTakeMoreThanTheMachineHasAreRefusedUpFront) {
  if (tsm::test::address_sanitizer) GTEST_SKIP() << "under AddressSanitizer the bound is on resident memory, not ulimit -v";
  // 80,001 contact nodes on a beam of 80,000 elements, 6.4·10⁹ contact and candidate element
  // pairs: a side each (two bits) should every node move beyond the broad phase's reach at once
  // (the candidate tables are the one contact entry's, shared): 3.2 GB, more than ulimit -v leaves.
  const std::string model = write("contacts.json", beam_under_contact_nodes(80'000, 80'001));
  const Outcome o = run_cli_bounded("run " + model + " --out " + out(), 2 * gigabyte, seconds);
  expect_over_budget(o, model, "contacts: the run needs ~");
  const std::string part = "(80,001 contacts with 6,400,080,000 candidate elements ";
  const size_t at = o.output.find(part);
  ASSERT_NE(at, std::string::npos) << o.output;
  // The contacts' part by hand: per candidate ¼ B × 6.4·10⁹ = 1.60 GB; per contact its state,
  // reference, kept response and 51 iterates' points, 80,001 × 4,132 B = 0.33 GB; the places of
  // 64 nodes let go off a free end, 16 B × 64 × 80,000 = 0.08 GB; past 32 contacts the sparse LU
  // kept as the fallback, ~5 KB per unknown × 240,000 = 1.2 GB: 3.21 GB, the rest (the table, the
  // elements' chords, the look-ahead's G) under 0.05 GB; stated to two digits.
  const std::string stated = o.output.substr(at + part.size());
  size_t digits = 0;
  const double contacts_gigabytes = std::stod(stated, &digits);
  EXPECT_EQ(stated.substr(digits, 4), " GB,") << o.output;
  EXPECT_NEAR(contacts_gigabytes, 3.25, 0.06) << o.output;
}

TEST_F(Limits, TheStatesTheOutputKeepsCountAgainstTheMachine) {
  if (tsm::test::address_sanitizer) GTEST_SKIP() << "under AddressSanitizer the bound is on resident memory, not ulimit -v";
  // Every state of 1,000 steps of 10⁴ elements: 800 MB (below the 8 GB every model is held to).
  json m = members_of(1, 10'000);
  m["analysis"] = {{"control", {{"type", "load"}, {"steps", 1000}}}, {"output", "all"}};
  const std::string model = write("all.json", m);
  const Outcome o = run_cli_bounded("run " + model + " --out " + out(), 500'000, seconds);
  expect_over_budget(o, model, "analysis.output: the run needs ~811 MB of memory (the state of 1,000 steps 800 MB,");
}

TEST_F(Limits, AModelFileIsHeldToTheMachineBeforeItIsParsed) {
  if (tsm::test::address_sanitizer) GTEST_SKIP() << "under AddressSanitizer the bound is on resident memory, not ulimit -v";
  // 40 MB of nodes parse into ~340 MB of document: held to what ulimit -v leaves before parsing.
  json m = members_of(1, 1);
  for (int k = 0; k < 1'000'000; ++k) m["nodes"].push_back({{"id", 10 + k}, {"x", 1.0 + k}, {"y", 2.5}});
  const std::string model = write("nodes.json", m);
  const Outcome o = run_cli_bounded("run " + model + " --out " + out(), 300'000, seconds);
  expect_over_budget(o, model, "(document): the run needs ~");
  EXPECT_NE(o.output.find("(the model file "), std::string::npos) << o.output;
}

}  // namespace
