// Progress on the terminal (app/progress): where stderr is a terminal (here a pseudo-terminal made
// by util-linux's `script`) a run's step lines give way to one another and a study draws a bar;
// through a pipe every line stays as it was. The closing lines are the same either way.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "support/cli.hpp"
#include "support/scratch_directory.hpp"

namespace {

using tsm::test::Outcome;
using tsm::test::run_command;

class Progress : public tsm::test::ScratchDirectory {
 protected:
  Progress() : ScratchDirectory("tsmframe-progress-") {}

  /// `tsmframe ARGUMENTS` with stderr a terminal (output as the terminal got it).
  Outcome on_terminal(const std::string& arguments) {
    return run_command("cd " + dir_.string() + " && TERM=xterm script -qec '" + std::string(TSMFRAME_CLI) + " " + arguments +
                       "' /dev/null");
  }
  /// The same through a pipe.
  Outcome piped(const std::string& arguments) {
    return run_command("cd " + dir_.string() + " && " + TSMFRAME_CLI + " " + arguments + " 2>&1");
  }

  static std::string example(const std::string& name) { return std::string(TSMFRAME_SOURCE_DIR) + "/examples/" + name; }
  static std::string study(const std::string& name) { return std::string(TSMFRAME_SOURCE_DIR) + "/studies/" + name; }
};

TEST_F(Progress, ARunsStepsShareOneLineOnATerminal) {
  const Outcome live = on_terminal("run " + example("portal-frame.json") + " --out a");
  EXPECT_EQ(live.exit_code, 0) << live.output;
  EXPECT_EQ(live.output.rfind("\r\033[Kstep 1 ", 0), 0u) << live.output;  // drawn over the line's start
  EXPECT_NE(live.output.find("\r\033[Kstep 10  load factor 1 "), std::string::npos) << live.output;  // the last step drawn
  EXPECT_NE(live.output.find("(force)\r\nconverged: 10 steps, 30 iterations; results in a/"), std::string::npos) << live.output;
  EXPECT_EQ(live.output.find("\nstep "), std::string::npos) << live.output;  // no step on a line of its own
  const Outcome lines = piped("run " + example("portal-frame.json") + " --out b");
  EXPECT_EQ(lines.exit_code, 0);
  EXPECT_EQ(lines.output.find('\r'), std::string::npos);
  EXPECT_NE(lines.output.find("\nstep 10  load factor 1 "), std::string::npos) << lines.output;
}

TEST_F(Progress, AnAttemptCutBackSaysWhyOnALineOfItsOwn) {
  // The strip on the coarse arch cuts one attempt back: its line says where it started and why
  // it failed, and stays (on a terminal too), before the step that then converges.
  const Outcome lines = piped("run " + example("strip-on-coarse-arch.json") + " --out a");
  EXPECT_EQ(lines.exit_code, 0) << lines.output;
  const size_t cut = lines.output.find("  cut back: ");
  ASSERT_NE(cut, std::string::npos) << lines.output;
  const size_t start = lines.output.rfind('\n', cut) + 1;
  EXPECT_EQ(lines.output.compare(start, 5, "step "), 0) << lines.output.substr(start, cut - start);
  EXPECT_NE(lines.output.substr(start, cut - start).find("  from load factor "), std::string::npos);
  EXPECT_GT(lines.output.find('\n', cut), cut + 12);  // a reason follows
  const Outcome live = on_terminal("run " + example("strip-on-coarse-arch.json") + " --out b");
  EXPECT_NE(live.output.find("cut back: "), std::string::npos);
  EXPECT_EQ(piped("run " + example("strip-on-coarse-arch.json") + " --out c -q").output.find("cut back"), std::string::npos);
}

/// The rows of a study's study.csv whose "converged" column (the seventh) is false.
int rows_not_converged(const std::filesystem::path& csv) {
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);  // the header
  int count = 0;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::string field;
    for (int k = 0; k < 7; ++k) std::getline(fields, field, ',');  // no comma before the seventh
    count += field == "false";
  }
  return count;
}

TEST_F(Progress, AStudyDrawsABarOnATerminal) {
  const Outcome live = on_terminal("study " + study("fig7-contact-edge.json") + " --out s -j 2");
  EXPECT_EQ(live.exit_code, 1) << live.output;  // some of its cases are meant not to converge
  // How many do is the study's (the paper's law at the element's end is sensitive to round-off):
  // the bar and the summary say what its rows say.
  const std::string failed = std::to_string(rows_not_converged(dir_ / "s" / "study.csv"));
  EXPECT_NE(failed, "0");
  EXPECT_NE(live.output.find("\r\033[K[########################] 48/48 cases, " + failed + " not converged, "),
            std::string::npos) << live.output;
  EXPECT_EQ(live.output.find("case 1/48"), std::string::npos);
  EXPECT_NE(live.output.find(" elapsed\r\n" + study("fig7-contact-edge.json") + ": 48 cases, " + failed + " did not converge"),
            std::string::npos) << live.output;
  const Outcome lines = piped("study " + study("fig7-contact-edge.json") + " --out t -j 2");
  EXPECT_EQ(lines.output.find('\r'), std::string::npos);
  EXPECT_NE(lines.output.find("[48 done]"), std::string::npos);
}

}  // namespace
