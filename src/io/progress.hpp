#pragma once
// A progress line on stderr for commands that can run longer than a few seconds (fit
// evaluations, reproduce runs, bench settings, a long single run). On a terminal: one line
// redrawn in place at most 5 times a second. Otherwise (a log file, a cluster job): one plain
// line every `log_period_s`, so a log shows life without filling up. Nothing when quiet, and
// nothing before `delay_s` has passed, so short commands stay silent. Thread-safe.
// Any other line goes through print_line, which erases a line drawn in place first (else the
// two would be glued on one terminal line); the progress line is redrawn at its next update.
#include <chrono>
#include <cstdio>
#include <string>

namespace asperity::io {

// "45s", "3m07s", "2h05m"; "?" when not finite.
std::string duration_text(double seconds);

// Remaining time by the rate so far: elapsed × (total − done) / done; NaN before any progress.
double eta_seconds(double elapsed_s, double done, double total);

// `line` and a newline on `to` (stdout or stderr), flushed, after erasing a progress line drawn
// in place on the terminal. Thread-safe, one whole line at a time.
void print_line(std::FILE* to, const std::string& line);

class ProgressLine {
 public:
  // `what` names the command ("fit"), `unit` what is counted ("evaluations").
  ProgressLine(std::string what, std::string unit, double total, bool quiet, double delay_s = 2.0,
               double log_period_s = 30.0);
  ~ProgressLine();
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  void update(double done, const std::string& extra = "");
  void set_total(double total);
  // Ends a line drawn on a terminal (as the destructor does), so what prints next starts afresh.
  void close();
  // The line as it would print now (for tests and for logs).
  std::string text(double done, double elapsed_s, const std::string& extra) const;

 private:
  friend void print_line(std::FILE* to, const std::string& line);
  using Clock = std::chrono::steady_clock;
  std::string what_, unit_;
  double total_;
  bool quiet_, tty_;
  double delay_s_, log_period_s_;
  Clock::time_point start_, last_;
  bool drawn_ = false;
};

}  // namespace asperity::io
