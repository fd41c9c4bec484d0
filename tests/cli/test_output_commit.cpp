// The output directory under interruption and system failure (io/output_directory.hpp): Ctrl-C
// and SIGTERM keep every converged step (exit 1); a file beyond the size limit, a directory that
// cannot be made and a full disk are exit 3 with the OS's reason, the previous outputs untouched
// and no temporaries left; dead runs' temporaries are removed, a live run's are not; a directory
// holding what tsmframe does not write, or a mount point, is not replaced. (SIGKILL at random moments:
// tests/robustness/kill_at_random.py.)
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "support/cli.hpp"
#include "support/scratch_directory.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

using tsm::test::Outcome;
using tsm::test::run_cli;
using tsm::test::run_cli_bounded;
using tsm::test::run_command;

/// A cantilever rolled up by a tip moment, 400 elements, in `steps` load steps keeping only the
/// last state: 10⁶ steps take minutes (~0.1 ms each), long enough for any signal to come first.
json rolled_cantilever(int steps) {
  return json::parse(R"({
    "format": "tsmframe-model/1", "title": "rolled",
    "materials": {"steel": {"E": 2.05e11, "G": 7.9e10}},
    "sections": {"s": {"A": 0.01, "I": 8.333333333333335e-06, "shear_area": 0.008333333333333335}},
    "nodes": [{"id": 1, "x": 0.0, "y": 0.0}, {"id": 2, "x": 10.0, "y": 0.0}],
    "members": [{"from": 1, "to": 2, "divisions": 400, "element": "timoshenko", "material": "steel", "section": "s"}],
    "supports": [{"node": 1, "type": "fixed"}],
    "loads": [{"node": 2, "mz": 1073377.489976513}],
    "analysis": {"control": {"type": "load", "steps": )" +
                     std::to_string(steps) + R"(}, "output": "last"}})");
}

/// This host's name as a temporary directory's name carries it (io/output_directory.cpp).
std::string host_name() {
  char buffer[256] = {};
  std::string host = ::gethostname(buffer, sizeof buffer - 1) == 0 && buffer[0] ? buffer : "localhost";
  for (char& c : host)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_')) c = '_';
  return host;
}

/// A process id no process has (a child that has ended and been waited for).
long dead_pid() {
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  ::waitpid(child, nullptr, 0);
  return child;
}

class OutputCommit : public tsm::test::ScratchDirectory {
 protected:
  OutputCommit() : ScratchDirectory("tsmframe-commit-") {}

  /// A converged run's outputs in `out`: the previous outputs the next run must keep or replace whole.
  void previous_outputs(const fs::path& out) {
    const Outcome o = run_cli("run " + write("previous.json", rolled_cantilever(2)) + " -q --out " + out.string());
    ASSERT_EQ(o.exit_code, 0) << o.output;
  }
  /// Every file under `directory` with its content.
  static std::map<std::string, std::string> contents(const fs::path& directory) {
    std::map<std::string, std::string> files;
    for (const auto& entry : fs::recursive_directory_iterator(directory)) {
      if (!entry.is_regular_file()) continue;
      std::ostringstream text;
      text << std::ifstream(entry.path()).rdbuf();
      files[fs::relative(entry.path(), directory).string()] = text.str();
    }
    return files;
  }
  /// Temporaries beside or in the outputs: tsmframe's directories and the files of old versions.
  std::vector<std::string> temporaries() const {
    std::vector<std::string> found;
    for (const auto& entry : fs::recursive_directory_iterator(dir_)) {
      const std::string name = entry.path().filename().string();
      if (name.find(".tsmframe-") != std::string::npos || name.find(".tmp-") != std::string::npos) found.push_back(name);
    }
    return found;
  }
  static size_t lines(const std::string& text) { return std::count(text.begin(), text.end(), '\n'); }
};

TEST_F(OutputCommit, CtrlCAndSigtermWriteEveryConvergedStepAndExitOne) {
  const std::string model = write("long.json", rolled_cantilever(1'000'000));
  for (const std::string signal : {"INT", "TERM"}) {
    const fs::path out = dir_ / ("out-" + signal);
    previous_outputs(out);
    const Outcome o = run_command("timeout --preserve-status -s " + signal + " 1 " + TSMFRAME_CLI + " run " + model +
                                  " -q --threads 1 --out " + out.string() + " 2>&1");
    EXPECT_EQ(o.exit_code, 1) << signal << ": " << o.output;
    EXPECT_EQ(lines(o.output), 1u) << o.output;
    EXPECT_NE(o.output.find("SIG" + signal + ": interrupted on request before step "), std::string::npos) << o.output;
    const json results = json::parse(std::ifstream(out / "results.json"));
    EXPECT_EQ(results["status"], "interrupted");
    const size_t steps = results["steps"].size();
    EXPECT_GT(steps, 0u);
    for (size_t k = 0; k < steps; ++k) {  // every converged step, in order, none failed
      EXPECT_EQ(results["steps"][k]["step"], k + 1);
      EXPECT_EQ(results["steps"][k]["converged"], true);
    }
    EXPECT_NE(results["message"].get<std::string>().find("before step " + std::to_string(steps + 1)), std::string::npos);
    std::ostringstream csv;
    csv << std::ifstream(out / "steps.csv").rdbuf();
    EXPECT_EQ(lines(csv.str()), steps + 1);  // the header and one row per converged step
    EXPECT_EQ(csv.str().rfind("\n" + std::to_string(steps) + ","), csv.str().rfind('\n', csv.str().size() - 2));
  }
  EXPECT_TRUE(temporaries().empty());
}

TEST_F(OutputCommit, AFileBeyondTheSizeLimitIsExitThreeWithTheReasonAndKeepsThePreviousOutputs) {
  const fs::path out = dir_ / "out";
  previous_outputs(out);
  const auto before = contents(out);
  json model = rolled_cantilever(200);
  model["analysis"]["output"] = "all";  // a results.json of some MB; the limit 100 kB (RLIMIT_FSIZE: EFBIG)
  const Outcome o = run_command("prlimit --fsize=100000 " + std::string(TSMFRAME_CLI) + " run " + write("big.json", model) +
                                " -q --vtk --out " + out.string() + " 2>&1");
  EXPECT_EQ(o.exit_code, 3) << o.output;
  EXPECT_EQ(lines(o.output), 1u) << o.output;
  EXPECT_NE(o.output.find("File too large"), std::string::npos) << o.output;
  EXPECT_TRUE(contents(out) == before) << "the previous outputs changed";
  EXPECT_TRUE(temporaries().empty()) << temporaries().front();
}

TEST_F(OutputCommit, AnOutputDirectoryThatCannotBeMadeIsExitThreeBeforeTheAnalysis) {
  // Under /proc no directory can be made, root or not; the analysis (minutes) must not start.
  const std::string model = write("long.json", rolled_cantilever(1'000'000));
  for (const std::string out : {"/proc/tsmframe-no-such/out", "/proc/version/out"}) {
    const Outcome o = run_cli_bounded("run " + model + " --out " + out, 2'000'000, 20);
    EXPECT_EQ(o.exit_code, 3) << out << ": " << o.output;
    EXPECT_EQ(lines(o.output), 1u) << o.output;
    EXPECT_NE(o.output.find("tsmframe: /proc/"), std::string::npos) << o.output;
    EXPECT_EQ(o.output.find("step 1"), std::string::npos) << o.output;
  }
}

TEST_F(OutputCommit, AFullDiskIsExitThreeWithTheReasonAndKeepsThePreviousOutputs) {
  // A 512 kB tmpfs in a mount namespace of a user namespace (no privilege needed where the
  // system allows user namespaces); skipped where it cannot be mounted.
  const fs::path disk = dir_ / "disk", saved = dir_ / "saved";
  fs::create_directories(disk);
  json model = rolled_cantilever(200);
  model["analysis"]["output"] = "all";
  const std::string cli = TSMFRAME_CLI, small = write("previous.json", rolled_cantilever(2)), big = write("big.json", model);
  const std::string script = "mount -t tmpfs -o size=512k tmpfs " + disk.string() + " || exit 99; " + cli + " run " +
                             small + " -q --out " + disk.string() + "/out || exit 98; cp -r " + disk.string() + "/out " +
                             saved.string() + "; " + cli + " run " + big + " -q --out " + disk.string() +
                             "/out; echo \"exit $?\"; ls -A " + disk.string() + "; diff -r " + disk.string() + "/out " +
                             saved.string() + " && echo unchanged; " + cli + " run " + small + " -q --out " + disk.string() +
                             " 2>/dev/null; echo \"mount point $?\"";
  const Outcome o = run_command("unshare --user --map-root-user --mount sh -c '" + script + "' 2>&1");
  if (o.exit_code == 99 || o.output.find("unshare: ") != std::string::npos)
    GTEST_SKIP() << "no tmpfs can be mounted here (user namespaces not allowed?): " << o.output;
  EXPECT_NE(o.output.find("No space left on device\nexit 3\nout\nunchanged\n"), std::string::npos) << o.output;
  EXPECT_EQ(lines(o.output), 5u) << o.output;  // one line from tsmframe; nothing but `out` on the disk
  // The disk's mount point itself cannot be replaced by a rename: refused before the analysis.
  EXPECT_NE(o.output.find("\nmount point 2\n"), std::string::npos) << o.output;
}

TEST_F(OutputCommit, DeadRunsTemporariesAreRemovedALiveRunsAreNot) {
  const std::string host = host_name();
  const fs::path dead = dir_ / (".out.tsmframe-" + host + "-" + std::to_string(dead_pid()));
  const fs::path live = dir_ / (".other.tsmframe-" + host + "-" + std::to_string(::getpid()));
  const fs::path foreign_host = dir_ / (".out.tsmframe-elsewhere-" + std::to_string(dead_pid()));
  // A dead run's previous outputs moved aside (a filesystem without RENAME_EXCHANGE) go back.
  const fs::path aside = dir_ / (".moved.previous.tsmframe-" + host + "-" + std::to_string(dead_pid()));
  for (const fs::path& d : {dead, live, foreign_host, aside}) {
    fs::create_directories(d);
    std::ofstream(d / "results.json") << "{}";
  }
  const Outcome o = run_cli("run " + write("m.json", rolled_cantilever(2)) + " -q --out " + (dir_ / "out").string());
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_FALSE(fs::exists(dead));
  EXPECT_TRUE(fs::exists(live));
  EXPECT_TRUE(fs::exists(foreign_host));  // another host's process ids say nothing here
  EXPECT_FALSE(fs::exists(aside));
  EXPECT_TRUE(fs::exists(dir_ / "moved" / "results.json"));
}

TEST_F(OutputCommit, ADirectoryHoldingWhatTsmframeDoesNotWriteIsNotReplaced) {
  const fs::path out = dir_ / "out";
  previous_outputs(out);
  std::ofstream(out / "notes.txt") << "mine";
  const auto before = contents(out);
  json replacing = rolled_cantilever(3);
  replacing["title"] = "replacing";
  const Outcome o = run_cli("run " + write("m.json", replacing) + " -q --out " + out.string());
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_EQ(lines(o.output), 1u) << o.output;
  EXPECT_NE(o.output.find("holds notes.txt, which tsmframe does not write there"), std::string::npos) << o.output;
  EXPECT_TRUE(contents(out) == before) << "the previous outputs changed";
  EXPECT_TRUE(temporaries().empty());
  // The working directory (or one holding it) cannot be replaced from within: refused.
  const Outcome here = run_command("cd " + out.string() + " && " + TSMFRAME_CLI + " run " + (dir_ / "m.json").string() +
                                   " -q --out . 2>&1");
  EXPECT_EQ(here.exit_code, 2) << here.output;
  EXPECT_NE(here.output.find("tsmframe: .: is (or holds) the working directory"), std::string::npos) << here.output;
  EXPECT_TRUE(contents(out) == before) << "the previous outputs changed";
  // A file where the directory should be is refused as well; the outputs of an older version
  // with their leftovers (results.json.tmp-PID) are replaced whole.
  EXPECT_EQ(run_cli("run " + (dir_ / "m.json").string() + " -q --out " + (out / "notes.txt").string()).exit_code, 2);
  fs::remove(out / "notes.txt");
  std::ofstream(out / "results.json.tmp-12345") << "{";
  EXPECT_EQ(run_cli("run " + (dir_ / "m.json").string() + " -q --out " + out.string()).exit_code, 0);
  EXPECT_TRUE(temporaries().empty());
  EXPECT_EQ(json::parse(std::ifstream(out / "results.json"))["title"], "replacing");
}

}  // namespace
