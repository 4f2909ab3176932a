#pragma once

#include <chrono>
#include <cstdio>
#include <string>

namespace alignset::cli {

// Progress on stderr: a redrawn bar with rate and ETA on a terminal, plain
// lines (at most one every `line_interval`) when stderr is a file or pipe, so
// logs stay readable.
class Progress {
 public:
  explicit Progress(std::string label, double line_interval_s = 2.0);
  // `done` of `total` units; `detail` is appended (loss, learning rate...).
  void Update(double done, double total, const std::string& detail);
  // Ends the bar's line (terminal) or prints a final line.
  void Finish(const std::string& detail);

 private:
  std::string label_;
  bool tty_;
  double line_interval_s_;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_line_;
  bool drawn_ = false;
};

std::string FormatDuration(double seconds);

}  // namespace alignset::cli
