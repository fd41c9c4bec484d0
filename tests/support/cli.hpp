#pragma once
// Runs the tsmframe command (TSMFRAME_CLI, set by CMake) as a user would, capturing its output.

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace tsm::test {

struct Outcome {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};

/// Runs a shell command line, capturing its output.
inline Outcome run_command(const std::string& command) {
  Outcome outcome;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return outcome;
  std::array<char, 4096> buffer{};
  while (size_t n = fread(buffer.data(), 1, buffer.size(), pipe)) outcome.output.append(buffer.data(), n);
  const int status = pclose(pipe);
  outcome.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return outcome;
}

inline Outcome run_cli(const std::string& arguments) { return run_command(std::string(TSMFRAME_CLI) + " " + arguments + " 2>&1"); }

/// run_cli within `kilobytes` of address space and `seconds`: a run that would allocate without
/// end fails its test (an abort, exit 134; the time limit, 124) instead of exhausting the machine.
inline Outcome run_cli_bounded(const std::string& arguments, long kilobytes, int seconds) {
  return run_command("ulimit -v " + std::to_string(kilobytes) + "; timeout " + std::to_string(seconds) + " " +
                     std::string(TSMFRAME_CLI) + " " + arguments + " 2>&1");
}

}  // namespace tsm::test
