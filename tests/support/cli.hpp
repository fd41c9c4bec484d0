#pragma once
// Runs the tsmframe command (TSMFRAME_CLI, set by CMake) as a user would, capturing its output.

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace tsm::test {

/// Whether this build (and the command it runs) has AddressSanitizer (scripts/sanitize.sh).
#if defined(__SANITIZE_ADDRESS__)  // g++
#define TSM_TEST_ADDRESS_SANITIZER 1
#elif defined(__has_feature)  // clang
#if __has_feature(address_sanitizer)
#define TSM_TEST_ADDRESS_SANITIZER 1
#endif
#endif
#ifdef TSM_TEST_ADDRESS_SANITIZER
inline constexpr bool address_sanitizer = true;
#else
inline constexpr bool address_sanitizer = false;
#endif

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
/// Under AddressSanitizer (scripts/sanitize.sh), which reserves terabytes of address space for
/// its shadow, the bound is on resident memory instead (the sanitizer's report, an abort), and the
/// time limit is ten times longer (an instrumented -O1 build runs 5–10 times slower).
inline Outcome run_cli_bounded(const std::string& arguments, long kilobytes, int seconds) {
  const std::string bound = address_sanitizer ? "ASAN_OPTIONS=\"$ASAN_OPTIONS:hard_rss_limit_mb=" + std::to_string(kilobytes / 1024) + "\" "
                                              : "ulimit -v " + std::to_string(kilobytes) + "; ";
  return run_command(bound + "timeout " + std::to_string(address_sanitizer ? 10 * seconds : seconds) + " " + std::string(TSMFRAME_CLI) + " " + arguments + " 2>&1");
}

}  // namespace tsm::test
