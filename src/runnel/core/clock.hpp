// SPDX-License-Identifier: MIT
#pragma once
#include <cmath>

namespace runnel {

// Work that runs on the simulated clock rather than every step (the talus relaxation, an erosion
// exchange interval): the time a step [time, time + dt] credits to work done every `interval`
// seconds. The interval once for each multiple of it the clock crosses, 0 for the steps between,
// and dt itself with an interval of 0 (every step). The credits add up to the clock, to within the
// last interval, and follow from the clock alone, so a resumed run does the work when the
// uninterrupted one did.
inline double interval_credit(double interval, double time, double dt) {
  if (interval <= 0) return dt;
  return interval * (std::floor((time + dt) / interval) - std::floor(time / interval));
}

}  // namespace runnel
