#include "client/progress.h"

#include <unistd.h>

#include <cmath>

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

Progress::Progress(std::string label, double line_interval_s)
    : label_(std::move(label)),
      tty_(isatty(STDERR_FILENO) != 0),
      line_interval_s_(line_interval_s),
      start_(std::chrono::steady_clock::now()),
      last_line_(start_) {}

void Progress::Update(double done, double total, const std::string& detail) {
  const auto now = std::chrono::steady_clock::now();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double frac = total > 0 ? std::min(1.0, done / total) : 0.0;
  const double eta = frac > 0 ? elapsed * (1.0 - frac) / frac : NAN;
  if (tty_) {
    constexpr int kWidth = 30;
    const int filled = static_cast<int>(frac * kWidth);
    std::string bar(filled, '#');
    bar.append(kWidth - filled, '.');
    std::fprintf(stderr, "\r%s [%s] %3.0f%% %s<%s %s\x1b[K", label_.c_str(), bar.c_str(), 100 * frac,
                 FormatDuration(elapsed).c_str(), FormatDuration(eta).c_str(), detail.c_str());
    std::fflush(stderr);
    drawn_ = true;
    return;
  }
  if (std::chrono::duration<double>(now - last_line_).count() < line_interval_s_) return;
  last_line_ = now;
  std::fprintf(stderr, "%s %.0f/%.0f elapsed %s eta %s %s\n", label_.c_str(), done, total,
               FormatDuration(elapsed).c_str(), FormatDuration(eta).c_str(), detail.c_str());
}

void Progress::Finish(const std::string& detail) {
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  if (tty_ && drawn_) std::fprintf(stderr, "\r\x1b[K");
  std::fprintf(stderr, "%s done in %s %s\n", label_.c_str(), FormatDuration(elapsed).c_str(),
               detail.c_str());
}

}  // namespace alignset::cli
