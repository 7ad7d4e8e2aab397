// SPDX-License-Identifier: MIT
#pragma once
#include <string>

#include "runnel/core/heightmap.hpp"
#include "runnel/io/json.hpp"

namespace runnel {

// How a terrain's heights come in steps. A DEM stored in whole metres (or scaled from one) is a
// staircase: level plateaus joined by risers one step high. The bed's slope then sits on the risers
// alone, and an erosion law driven by it digs one-vertex pits on the flats (README, "On terrains
// the defaults were not tuned for": the Jacksboro DEM's south-east crop). Generated terrains and
// 16-bit PNGs have neighbours at exactly one height almost nowhere.
struct HeightSteps {
  double step = 0;            // m, the smallest nonzero height difference between 4-neighbours
  double level_share = 0;     // of the 4-neighbour pairs, the share at exactly one height
  double one_step_share = 0;  // the share exactly one step apart (within 5 % of it)
  // Of the runs of three vertices in a row or column, the share where a level pair meets a one-step
  // pair: the end of a tread. A staircase has one at every riser; a plane of constant slope has
  // heights in equal steps (one-step pairs along its slope, level ones across it) but none.
  double tread_end_share = 0;
  // Level pairs, at least half as many one-step risers, and treads that end on them: a plain's
  // flat floor has the first without the second, a tilted plane the first two without the third.
  bool stepped() const;
  std::string caution() const;  // one line for `runnel run`, empty when not stepped
  // height_step, level_share, one_step_share, tread_end_share and stepped: the fields
  // metrics.json's terrain block and `runnel info --json` report.
  JsonObject json() const;
};

HeightSteps height_steps(const Heightmap& terrain);

}  // namespace runnel
