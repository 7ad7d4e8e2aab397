// SPDX-License-Identifier: MIT
#pragma once
#include <epoxy/gl.h>

#include <array>
#include <chrono>

namespace runnel::viewer {

// --bench: where a frame's time goes, phase by phase. Each lap first waits for the GL to finish
// what it was given (glFinish), so a phase's time is its work done, not only queued. Off, it does
// nothing (and costs the frame no wait).
class FrameTimer {
 public:
  enum Phase {
    kSimulate,      // the model's steps
    kReadWater,     // the model's water view: SPH's particles read back and binned
    kTerrain,       // the terrain's heights and normals uploaded, and drawn with its water
    kWaterSurface,  // the water's surface built (SPH: at the particles' scale) and uploaded
    kPanel,         // the panel and the rain streaks
    kOther,         // the mass balance read every 10 frames, a recording's frame
    kPhases
  };
  static constexpr const char* kNames[kPhases] = {"simulate",      "read_water", "terrain",
                                                  "water_surface", "panel",      "other"};

  explicit FrameTimer(bool on) : on_(on) {}
  bool on() const { return on_; }
  // The frame's first phase begins now.
  void begin() {
    if (on_) last_ = std::chrono::steady_clock::now();
  }
  // The time since the last lap (or begin) goes to `phase`.
  void lap(Phase phase) {
    if (!on_) return;
    glFinish();
    const auto now = std::chrono::steady_clock::now();
    if (counting_) seconds_[phase] += std::chrono::duration<double>(now - last_).count();
    last_ = now;
  }
  // Laps count from now on (after the warm-up frames).
  void start_counting() { counting_ = on_; }
  double seconds(Phase phase) const { return seconds_[phase]; }
  double total() const {
    double sum = 0;
    for (double s : seconds_) sum += s;
    return sum;
  }

 private:
  bool on_, counting_ = false;
  std::chrono::steady_clock::time_point last_;
  std::array<double, kPhases> seconds_{};
};

}  // namespace runnel::viewer
