// SPDX-License-Identifier: MIT
#include "runnel/io/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>

namespace runnel {
namespace {

std::string clock_text(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "--:--";
  const long s = std::lround(seconds);
  char buf[32];
  if (s >= 3600)
    std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", s / 3600, (s / 60) % 60, s % 60);
  else
    std::snprintf(buf, sizeof buf, "%ld:%02ld", s / 60, s % 60);
  return buf;
}

}  // namespace

Progress::Progress(Mode mode)
    : mode_(mode), start_(std::chrono::steady_clock::now()), last_draw_(start_) {}

Progress::Mode Progress::mode_for_stderr(bool quiet) {
  if (quiet) return Mode::kQuiet;
  return isatty(STDERR_FILENO) ? Mode::kBar : Mode::kLines;
}

void Progress::update(double fraction, const std::string& status, bool report_line) {
  const auto now = std::chrono::steady_clock::now();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  fraction = std::clamp(fraction, 0.0, 1.0);
  const double eta = fraction > 0 ? elapsed * (1.0 - fraction) / fraction : NAN;
  if (mode_ == Mode::kBar) {
    if (std::chrono::duration<double>(now - last_draw_).count() < 0.1 && fraction < 1.0) return;
    last_draw_ = now;
    const int width = 24, filled = static_cast<int>(fraction * width);
    std::string bar(filled, '#');
    bar.append(width - filled, '.');
    std::fprintf(stderr, "\r[%s] %3.0f%% %s ETA %s   ", bar.c_str(), 100.0 * fraction,
                 status.c_str(), clock_text(eta).c_str());
    std::fflush(stderr);
  } else if (mode_ == Mode::kLines && report_line) {
    std::fprintf(stderr, "%5.1f%% %s elapsed %s ETA %s\n", 100.0 * fraction, status.c_str(),
                 clock_text(elapsed).c_str(), clock_text(eta).c_str());
  }
}

void Progress::abandon() {
  if (mode_ == Mode::kBar) std::fprintf(stderr, "\r%-100s\r", "");
}

void Progress::finish(const std::string& status) {
  if (mode_ == Mode::kQuiet) return;
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  if (mode_ == Mode::kBar) std::fprintf(stderr, "\r%-100s\r", "");
  std::fprintf(stderr, "done: %s in %s\n", status.c_str(), clock_text(elapsed).c_str());
}

}  // namespace runnel
