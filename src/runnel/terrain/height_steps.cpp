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
//   (one flat, no staircase);
// - planes of constant slope: up to 50 % level and 50 % one step apart (heights in equal steps),
//   but no tread ends; the Jacksboro DEM and its crops: 0.40–0.98 % tread ends.
constexpr double kSteppedLevelShare = 0.01;
constexpr double kSteppedOneStepShare = 0.02;
constexpr double kSteppedRisersPerLevel = 0.5;
constexpr double kSteppedTreadEndShare = 0.002;

}  // namespace

bool HeightSteps::stepped() const {
  return step > 0 && level_share >= kSteppedLevelShare && one_step_share >= kSteppedOneStepShare &&
         one_step_share >= kSteppedRisersPerLevel * level_share &&
         tread_end_share >= kSteppedTreadEndShare;
}

std::string HeightSteps::caution() const {
  if (!stepped()) return "";
  char line[400];
  std::snprintf(line, sizeof line,
                "the terrain's heights come in steps of %.3g m (%.1f %% of neighbouring vertices "
                "level, %.1f %% one step apart, treads ending on risers), as a DEM stored in whole "
                "units does: erosion "
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
      .add("tread_end_share", tread_end_share)
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

// Calls visit(|Δh₁|, |Δh₂|) for every run of three vertices in a row or a column: the two height
// differences along it.
template <typename Visit>
void for_each_run_of_three(const Heightmap& t, Visit visit) {
  for (int j = 0; j < t.ny; ++j)
    for (int i = 0; i < t.nx; ++i) {
      if (i + 2 < t.nx)
        visit(std::fabs(t.at(i + 1, j) - t.at(i, j)), std::fabs(t.at(i + 2, j) - t.at(i + 1, j)));
      if (j + 2 < t.ny)
        visit(std::fabs(t.at(i, j + 1) - t.at(i, j)), std::fabs(t.at(i, j + 2) - t.at(i, j + 1)));
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
  const auto is_one_step = [&](float d) {
    return d > 0 && std::fabs(d - smallest) <= 0.05f * smallest;
  };
  long long one_step = 0;
  for_each_neighbour_difference(terrain, [&](float d) {
    if (is_one_step(d)) ++one_step;
  });
  s.one_step_share = static_cast<double>(one_step) / static_cast<double>(pairs);
  long long runs = 0, tread_ends = 0;
  for_each_run_of_three(terrain, [&](float first, float second) {
    ++runs;
    if ((first == 0 && is_one_step(second)) || (is_one_step(first) && second == 0)) ++tread_ends;
  });
  if (runs > 0) s.tread_end_share = static_cast<double>(tread_ends) / static_cast<double>(runs);
  return s;
}

}  // namespace runnel
