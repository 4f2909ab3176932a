#include "cli/progress.h"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>

#include "core/util/number_text.h"

namespace alignset::cli {

std::string FormatDuration(double s) {
  if (!std::isfinite(s) || s < 0) return "--:--";
  char buf[32];
  const long t = std::lround(s);
  if (t >= 3600) {
    std::snprintf(buf, sizeof(buf), "%ld:%02ld:%02ld", t / 3600, (t / 60) % 60, t % 60);
  } else {
    std::snprintf(buf, sizeof(buf), "%02ld:%02ld", t / 60, t % 60);
  }
  return buf;
}

int TerminalColumns(int fd) {
  winsize ws{};
  if (ioctl(fd, TIOCGWINSZ, &ws) == 0 && ws.ws_col > 0) return ws.ws_col;
  // A terminal that does not report its size (a serial line, some
  // emulators, a pseudo-terminal nobody sized): the shell's idea of it.
  if (const char* c = std::getenv("COLUMNS")) {
    auto v = ParseInt(c, "COLUMNS", 1, 100000);
    if (v.ok()) return static_cast<int>(*v);
  }
  return 80;
}

std::string BarLine(int columns, const std::string& label, double fraction, double elapsed,
                    double eta, const std::string& detail) {
  const size_t room = static_cast<size_t>(std::max(0, columns - 1));
  const double f = std::clamp(fraction, 0.0, 1.0);
  char percent[8];
  std::snprintf(percent, sizeof(percent), "%3.0f%%", 100 * f);
  std::string times = FormatDuration(elapsed);
  times.append("<").append(FormatDuration(eta));
  // "label [bar] pct times detail", the bar 30 cells wide where there is
  // room, down to 10; below that the bar, then the times are left out.
  const size_t fixed = label.size() + 1 + 1 + std::strlen(percent) + 1 + times.size();
  std::string line = label;
  line.push_back(' ');
  if (fixed + 2 + 10 <= room) {
    const size_t width = std::min<size_t>(30, room - fixed - 2);
    const size_t filled = static_cast<size_t>(f * static_cast<double>(width));
    line.push_back('[');
    line.append(filled, '#').append(width - filled, '.');
    line.append("] ").append(percent).append(" ").append(times);
  } else if (fixed - 1 <= room) {
    line.append(percent).append(" ").append(times);
  } else {
    line.append(percent);
  }
  if (!detail.empty() && line.size() + 2 <= room) {
    line.push_back(' ');
    line.append(detail, 0, room - line.size());
  }
  if (line.size() > room) line.resize(room);
  return line;
}

Progress::Progress(std::string label, double line_interval_s, FILE* stream)
    : label_(std::move(label)),
      stream_(stream),
      tty_(isatty(fileno(stream)) != 0),
      line_interval_s_(line_interval_s),
      start_(std::chrono::steady_clock::now()),
      last_line_(start_) {}

void Progress::Update(double done, double total, const std::string& detail) {
  const auto now = std::chrono::steady_clock::now();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double frac = total > 0 ? std::min(1.0, done / total) : 0.0;
  const double eta = frac > 0 ? elapsed * (1.0 - frac) / frac : NAN;
  if (tty_) {
    const std::string line =
        BarLine(TerminalColumns(fileno(stream_)), label_, frac, elapsed, eta, detail);
    // \r back to the start, the line, then erase what an older, longer line left.
    std::fprintf(stream_, "\r%s\x1b[K", line.c_str());
    std::fflush(stream_);
    drawn_ = true;
    return;
  }
  if (std::chrono::duration<double>(now - last_line_).count() < line_interval_s_) return;
  last_line_ = now;
  std::fprintf(stream_, "%s %.0f/%.0f elapsed %s eta %s %s\n", label_.c_str(), done, total,
               FormatDuration(elapsed).c_str(), FormatDuration(eta).c_str(), detail.c_str());
}

void Progress::Finish(const std::string& detail) {
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  if (tty_ && drawn_) std::fprintf(stream_, "\r\x1b[K");
  std::fprintf(stream_, "%s done in %s %s\n", label_.c_str(), FormatDuration(elapsed).c_str(),
               detail.c_str());
}

}  // namespace alignset::cli
