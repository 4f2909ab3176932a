#pragma once

#include <chrono>
#include <cstdio>
#include <string>

namespace alignset::cli {

// Progress on a stream (stderr by default): a redrawn bar with rate and ETA on
// a terminal, plain lines (at most one every `line_interval`) when the stream
// is a file or pipe, so logs stay readable. The bar fits the terminal: its
// width is read from the terminal itself at every redraw (a resize mid-run is
// followed), so a redraw never wraps and scrolls.
class Progress {
 public:
  explicit Progress(std::string label, double line_interval_s = 2.0, FILE* stream = stderr);
  // `done` of `total` units; `detail` is appended (loss, learning rate...).
  void Update(double done, double total, const std::string& detail);
  // Ends the bar's line (terminal) or prints a final line.
  void Finish(const std::string& detail);

 private:
  std::string label_;
  FILE* stream_;
  bool tty_;
  double line_interval_s_;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_line_;
  bool drawn_ = false;
};

std::string FormatDuration(double seconds);

// Columns of the terminal on `fd`: TIOCGWINSZ, else $COLUMNS, else 80.
int TerminalColumns(int fd);

// One redraw of the bar, at most `columns` - 1 characters (the last column is
// left free: writing into it makes some terminals wrap). Parts go as the width
// shrinks: the detail is cut first, then the bar narrows, then the times go.
std::string BarLine(int columns, const std::string& label, double fraction,
                    double elapsed_seconds, double eta_seconds, const std::string& detail);

}  // namespace alignset::cli
