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

inline Outcome run_cli(const std::string& arguments) {
  const std::string command = std::string(TSMFRAME_CLI) + " " + arguments + " 2>&1";
  Outcome outcome;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return outcome;
  std::array<char, 4096> buffer{};
  while (size_t n = fread(buffer.data(), 1, buffer.size(), pipe)) outcome.output.append(buffer.data(), n);
  const int status = pclose(pipe);
  outcome.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return outcome;
}

}  // namespace tsm::test
