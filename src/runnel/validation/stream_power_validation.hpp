// SPDX-License-Identifier: MIT
#pragma once
#include "runnel/io/json.hpp"

namespace runnel {

// `runnel validate stream-power` (docs/models.md "stream-power"): the implicit stream-power solver
// and the hillslope diffusion against their analytic steady states, each from a start that is not
// the answer, run until the heights stop changing.
struct SteadyStateCheck {
  double worst_relative =
      0;  // the largest |numerical − analytic| / analytic over the nodes checked
  double mean_relative = 0;
  double fitted_theta = 0;  // slope–area cases: −d log S / d log A, least squares
  int nodes = 0;            // nodes compared
  long long steps = 0;      // steps to steady state
};

// Fastscapelib's bedrock-channel case: 101 nodes 300 m apart, Hack's law A = 6.69 x^1.67 (x from
// the divide, 300 m at the top), U = K = 1e-3, m = 0.5, n as given, dt = 1e4 yr, from the profile
// h = 0.001 (x − x_outlet); run until the change of a step is below 1e-9 m (L2; fastscapelib stops
// at 1e-3 and compares with an absolute tolerance of 1e-5, looser than the slopes themselves);
// slopes at every node but the outlet against (U/K)^(1/n) A^(−m/n).
SteadyStateCheck stream_power_profile(double n);

// A 2-D grid (nx × nx, cell 100 m) under uniform uplift from low random relief, D8 with
// priority-flood, all edges base level: at steady state every node with an upstream area of at
// least `min_cells` cells has S = (U/K)^(1/n) A^(−m/n), and log S against log A has the slope −m/n.
SteadyStateCheck stream_power_grid(int nx, double n, int min_cells);

// Diffusion only: a ridge between base-level west and east edges (north and south closed), uplift
// U = 1 mm/yr, D = 1 m²/yr, 101 × 5 vertices 10 m apart, dt = 2 yr, from flat, until a step
// changes the heights by less than 1e-12 m (L2): the steady slope is S = U·x/D, x the distance from
// the divide, checked between every pair of neighbours along a row. Uplift and diffusion are split
// within a step, which leaves an error of order U·dt at the nodes next to the base level (0.4 % at
// dt = 20 yr, 0.04 % at 2 yr).
SteadyStateCheck hillslope_diffusion();

JsonObject json(const SteadyStateCheck& c);

}  // namespace runnel
