// SPDX-License-Identifier: MIT
#include "runnel/terrain/height_steps.hpp"

#include <cmath>
#include <cstdio>
#include <limits>

namespace runnel {
namespace {

// Shares of the 4-neighbour pairs, measured:
// - the Jacksboro DEM and its crops: 2.3–5.4 % level, 4–7 % one step apart (1.2–1.9 × level);
// - generated terrains and 16-bit PNGs: at most 0.6 % level, at most 0.1 % one step apart;
// - Fritz's pyramid and hemisphere on their plains: 49–67 % level, 0.4–1.2 % one step apart
//   (one flat, no staircase).
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

JsonObject HeightSteps::json() const {
  return JsonObject()
      .add("height_step", step)
      .add("level_share", level_share)
      .add("one_step_share", one_step_share)
      .add("stepped", stepped());
}

// Calls visit(|Δh|) for every pair of 4-neighbours; two passes over the grid, no copy of it (a
// DEM may be large).
template <typename Visit>
void for_each_neighbour_difference(const Heightmap& t, Visit visit) {
  for (int j = 0; j < t.ny; ++j)
    for (int i = 0; i < t.nx; ++i) {
      if (i + 1 < t.nx) visit(std::fabs(t.at(i + 1, j) - t.at(i, j)));
      if (j + 1 < t.ny) visit(std::fabs(t.at(i, j + 1) - t.at(i, j)));
    }
}

HeightSteps height_steps(const Heightmap& terrain) {
  HeightSteps s;
  float smallest = std::numeric_limits<float>::infinity();
  long long pairs = 0, level = 0;
  for_each_neighbour_difference(terrain, [&](float d) {
    ++pairs;
    if (d == 0)
      ++level;
    else
      smallest = std::fmin(smallest, d);
  });
  if (pairs == 0) return s;
  s.level_share = static_cast<double>(level) / static_cast<double>(pairs);
  if (!std::isfinite(smallest)) return s;  // every pair level: a flat terrain, no steps
  s.step = smallest;
  long long one_step = 0;
  for_each_neighbour_difference(terrain, [&](float d) {
    if (d > 0 && std::fabs(d - smallest) <= 0.05f * smallest) ++one_step;
  });
  s.one_step_share = static_cast<double>(one_step) / static_cast<double>(pairs);
  return s;
}

}  // namespace runnel
