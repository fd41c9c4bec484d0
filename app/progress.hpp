#pragma once
// Progress on the terminal: where stderr is a terminal, a run's step lines overwrite one another
// (a live line; failed attempts stay) and a study draws a bar with an estimate of the time left;
// elsewhere (a log file, a pipe, a batch system) every line stays, as before.

#include <chrono>
#include <cstddef>
#include <ostream>
#include <string>

namespace tsm::app {

/// Whether stderr is a terminal that moves its cursor (not TERM=dumb).
bool stderr_is_terminal();

/// Lines on `out` that replace the one before where `live` (a terminal), else one per line.
class LiveLine {
 public:
  LiveLine(std::ostream& out, bool live) : out_(out), live_(live) {}
  ~LiveLine() { finish(); }
  /// A line that the next one replaces (on a terminal, drawn ten times a second at most: a run of
  /// millions of short steps is not slowed by its terminal; the newest is drawn at the end).
  void passing(const std::string& line);
  /// A line that stays.
  void lasting(const std::string& line);
  /// Ends the live line, so that what follows starts on a line of its own.
  void finish();

 private:
  void draw(const std::string& line);

  std::ostream& out_;
  bool live_;
  bool open_ = false;  ///< a passing line is on the terminal, its newline not written
  std::string waiting_;  ///< the newest passing line not drawn yet
  std::chrono::steady_clock::time_point drawn_{};
};

/// "[##########··········] 50/100 cases, 3 not converged, 0:12 elapsed, ~0:12 left".
std::string progress_bar(std::size_t done, std::size_t total, std::size_t not_converged, std::chrono::seconds elapsed);

}  // namespace tsm::app
