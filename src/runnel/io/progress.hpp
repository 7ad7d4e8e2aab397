// SPDX-License-Identifier: MIT
#pragma once
#include <chrono>
#include <cstdio>
#include <string>

namespace runnel {

// Progress of a long run on stderr: a bar redrawn in place on a terminal, or one plain line per
// report when stderr is a file or a pipe (logs stay readable). Quiet prints nothing.
class Progress {
 public:
  enum class Mode { kBar, kLines, kQuiet };
  explicit Progress(Mode mode);
  static Mode mode_for_stderr(bool quiet);

  // fraction in [0, 1]; `status` is the run's own summary (steps, particles, time, ...).
  void update(double fraction, const std::string& status, bool report_line);
  // The run stopped with an error: the bar's line is cleared, so the error reads alone.
  void abandon();
  void finish(const std::string& status);

 private:
  Mode mode_;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_draw_;
};

}  // namespace runnel
