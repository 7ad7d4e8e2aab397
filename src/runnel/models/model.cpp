// SPDX-License-Identifier: MIT
#include "runnel/models/model.hpp"

#include <cmath>

namespace runnel {

const char* clock_name(ModelClock clock) {
  return clock == ModelClock::kSeconds ? "s" : clock == ModelClock::kYears ? "yr" : "iterations";
}

const char* clock_suffix(ModelClock clock) {
  return clock == ModelClock::kSeconds ? " s" : clock == ModelClock::kYears ? " yr" : "";
}

void Model::advance(double dt) {
  if (!(dt > 0)) return;
  if (info().clock == ModelClock::kIterations) {
    for (long long k = std::llround(dt); k > 0; --k) step();
    return;
  }
  // A relative tolerance, so that a clock summed from many steps still lands on the target.
  const double target = time() + dt;
  while (time() < target - 1e-12 * std::max(1.0, std::fabs(target))) step();
}

}  // namespace runnel
