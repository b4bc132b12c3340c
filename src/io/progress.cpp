#include "io/progress.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <mutex>

#include "io/numbers.hpp"

namespace asperity::io {

namespace {

// One terminal: every progress line and print_line take this lock, and `drawn_in_place` is the
// line standing unfinished on it (nullptr: none), which the next other line must erase.
std::mutex& terminal_mutex() {
  static std::mutex m;
  return m;
}
ProgressLine* drawn_in_place = nullptr;

}  // namespace

void print_line(std::FILE* to, const std::string& line) {
  const std::lock_guard<std::mutex> lock(terminal_mutex());
  if (drawn_in_place) {
    std::fputs("\r\033[K", stderr);
    std::fflush(stderr);
    drawn_in_place->drawn_ = false;  // redrawn at its next update, whatever its rate limit
    drawn_in_place = nullptr;
  }
  if (to != stdout) std::fflush(stdout);  // what a command printed before comes first
  std::fputs(line.c_str(), to);
  std::fputc('\n', to);
  std::fflush(to);
}

std::string duration_text(double s) {
  if (!std::isfinite(s)) return "?";
  char buf[32];
  const long t = std::lround(s);
  if (t >= 3600)
    std::snprintf(buf, sizeof buf, "%ldh%02ldm", t / 3600, (t / 60) % 60);
  else if (t >= 60)
    std::snprintf(buf, sizeof buf, "%ldm%02lds", t / 60, t % 60);
  else
    std::snprintf(buf, sizeof buf, "%lds", t);
  return buf;
}

double eta_seconds(double elapsed_s, double done, double total) {
  if (!(done > 0) || !(elapsed_s >= 0)) return NAN;
  return elapsed_s * std::max(0.0, total - done) / done;
}

ProgressLine::ProgressLine(std::string what, std::string unit, double total, bool quiet, double delay_s,
                           double log_period_s)
    : what_(std::move(what)),
      unit_(std::move(unit)),
      total_(total),
      quiet_(quiet),
      tty_(::isatty(2) == 1),
      delay_s_(delay_s),
      log_period_s_(log_period_s),
      start_(Clock::now()),
      last_(start_) {}

ProgressLine::~ProgressLine() { close(); }

void ProgressLine::close() {
  const std::lock_guard<std::mutex> lock(terminal_mutex());
  if (drawn_ && tty_) std::fputc('\n', stderr);
  drawn_ = false;
  if (drawn_in_place == this) drawn_in_place = nullptr;
}

void ProgressLine::set_total(double total) {
  const std::lock_guard<std::mutex> lock(terminal_mutex());
  total_ = total;
}

std::string ProgressLine::text(double done, double elapsed_s, const std::string& extra) const {
  char buf[256];
  std::snprintf(buf, sizeof buf, "%s: %s/%s %s, %s elapsed, ETA %s", what_.c_str(), io::format_count(done).c_str(),
                io::format_count(total_).c_str(), unit_.c_str(), duration_text(elapsed_s).c_str(),
                duration_text(eta_seconds(elapsed_s, done, total_)).c_str());
  std::string line = buf;
  if (!extra.empty()) line += ", " + extra;
  return line;
}

void ProgressLine::update(double done, const std::string& extra) {
  if (quiet_) return;
  const std::lock_guard<std::mutex> lock(terminal_mutex());
  const auto now = Clock::now();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  if (elapsed < delay_s_) return;
  const double since = std::chrono::duration<double>(now - last_).count();
  if (drawn_ && since < (tty_ ? 0.2 : log_period_s_)) return;
  last_ = now;
  drawn_ = true;
  const std::string line = text(done, elapsed, extra);
  if (tty_) {
    std::fprintf(stderr, "\r%s\033[K", line.c_str());
    drawn_in_place = this;
  } else {
    std::fprintf(stderr, "%s\n", line.c_str());
  }
  std::fflush(stderr);
}

}  // namespace asperity::io
