// SPDX-License-Identifier: MIT
#include "runnel/terrain/height_steps.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

namespace runnel {
namespace {

// Shares of the pairs, measured on the Jacksboro DEM and its crops (level 2.3–5.4 %, one step apart
// 4–7 %, 1.2–1.9 times the level share) against generated terrains and 16-bit PNGs (level ≤ 0.6 %,
// one step ≤ 0.1 %) and Fritz's pyramid and hemisphere on a plain (level 49–67 %, one step 0.4–1.2
// %: one flat, no staircase).
constexpr double kSteppedLevelShare = 0.01;
constexpr double kSteppedOneStepShare = 0.02;
constexpr double kSteppedRisersPerLevel = 0.5;

}  // namespace

bool HeightSteps::stepped() const {
  return step > 0 && level_share >= kSteppedLevelShare && one_step_share >= kSteppedOneStepShare &&
         one_step_share >= kSteppedRisersPerLevel * level_share;
}

std::string HeightSteps::caution() const {
  if (!stepped()) return "";
  char line[400];
  std::snprintf(line, sizeof line,
                "the terrain's heights come in steps of %.3g m (%.1f %% of neighbouring vertices "
                "level, %.1f %% one step apart), as a DEM stored in whole units does: erosion "
                "driven by the bed's slope gathers on the steps and digs one-vertex pits on the "
                "flats; smooth the terrain first (docs/terrain-formats.md, \"Stepped DEMs\")",
                step, 100 * level_share, 100 * one_step_share);
  return line;
}

HeightSteps height_steps(const Heightmap& terrain) {
  std::vector<float> differences;
  differences.reserve(2 * terrain.h.size());
  for (int j = 0; j < terrain.ny; ++j)
    for (int i = 0; i < terrain.nx; ++i) {
      if (i + 1 < terrain.nx)
        differences.push_back(std::fabs(terrain.at(i + 1, j) - terrain.at(i, j)));
      if (j + 1 < terrain.ny)
        differences.push_back(std::fabs(terrain.at(i, j + 1) - terrain.at(i, j)));
    }
  HeightSteps s;
  if (differences.empty()) return s;
  float smallest = std::numeric_limits<float>::infinity();
  long long level = 0;
  for (float d : differences) {
    if (d == 0)
      ++level;
    else
      smallest = std::fmin(smallest, d);
  }
  const double pairs = static_cast<double>(differences.size());
  s.level_share = level / pairs;
  if (!std::isfinite(smallest)) return s;  // every pair level: a flat terrain, no steps
  s.step = smallest;
  long long one_step = 0;
  for (float d : differences)
    if (d > 0 && std::fabs(d - smallest) <= 0.05f * smallest) ++one_step;
  s.one_step_share = one_step / pairs;
  return s;
}

}  // namespace runnel
