#include "progress.hpp"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace tsm::app {

bool stderr_is_terminal() {
  const char* term = std::getenv("TERM");
  return ::isatty(STDERR_FILENO) == 1 && !(term && std::strcmp(term, "dumb") == 0);
}

void LiveLine::draw(const std::string& line) {
  out_ << "\r\033[K" << line << std::flush;  // back to the line's start, cleared
  open_ = true;
  waiting_.clear();
  drawn_ = std::chrono::steady_clock::now();
}

void LiveLine::passing(const std::string& line) {
  if (!live_) {
    out_ << line << '\n';
    return;
  }
  if (std::chrono::steady_clock::now() - drawn_ < std::chrono::milliseconds(100)) waiting_ = line;
  else draw(line);
}

void LiveLine::lasting(const std::string& line) {
  if (live_ && !waiting_.empty()) draw(waiting_);  // the step before it, then this one below
  if (live_ && open_) out_ << '\n';
  out_ << line << '\n' << std::flush;
  open_ = false;
}

void LiveLine::finish() {
  if (live_ && !waiting_.empty()) draw(waiting_);
  if (open_) out_ << '\n' << std::flush;
  open_ = false;
}

namespace {

std::string clock_text(long seconds) {
  char text[32];
  if (seconds >= 3600) std::snprintf(text, sizeof text, "%ld:%02ld:%02ld", seconds / 3600, seconds / 60 % 60, seconds % 60);
  else std::snprintf(text, sizeof text, "%ld:%02ld", seconds / 60, seconds % 60);
  return text;
}

}  // namespace

std::string progress_bar(std::size_t done, std::size_t total, std::size_t not_converged, std::chrono::seconds elapsed) {
  constexpr int width = 24;
  const double fraction = total > 0 ? static_cast<double>(done) / static_cast<double>(total) : 1.0;
  const int filled = static_cast<int>(fraction * width);
  std::string bar = "[" + std::string(filled, '#') + std::string(width - filled, '.') + "] ";
  bar += std::to_string(done) + "/" + std::to_string(total) + " cases, " + std::to_string(not_converged) +
         " not converged, " + clock_text(elapsed.count()) + " elapsed";
  if (done > 0 && done < total) {
    const long left = static_cast<long>(static_cast<double>(elapsed.count()) * static_cast<double>(total - done) / static_cast<double>(done));
    bar += ", ~" + clock_text(left) + " left";
  }
  return bar;
}

}  // namespace tsm::app
