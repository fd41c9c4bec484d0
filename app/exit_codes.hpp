#pragma once
// The `tsmframe` command's exit status: 0 converged to the end; 1 ran but did not reach the end
// (results written: a step failed, or Ctrl-C / SIGTERM interrupted it); 2 bad input or usage; 3
// the system failed us (a file that cannot be written, memory run out).

namespace tsm::app {

inline constexpr int exit_converged = 0;
inline constexpr int exit_not_converged = 1;
inline constexpr int exit_bad_input = 2;
inline constexpr int exit_system = 3;

}  // namespace tsm::app
