// SPDX-License-Identifier: MIT
#pragma once
#include <vector>

#include "runnel/core/heightmap.hpp"
#include "runnel/core/parameters.hpp"

namespace runnel {

// Water standing on the terrain at t = 0 (docs/physics.md, "Standing water"): [[water.bodies]]
// rectangles in map metres filled up to a water level, and a raster of depths (water.depth). Every
// model with water starts from this depth per vertex; the volume is reported as initial water.

// The depth (m) per vertex of `terrain` (its grid, rows from the north): for each body, level −
// height where the vertex lies inside the rectangle and below the level; plus the raster's depth.
// Where bodies overlap, the higher level counts. All zeros when the scenario sets none. Throws an
// input error naming the body when its rectangle is empty, lies off the terrain or holds no vertex
// below its level, and naming the raster when a depth is negative or not finite.
std::vector<float> initial_water_depth(const Parameters& params, const Heightmap& terrain);

// Whether the scenario sets any standing water.
bool has_standing_water(const Parameters& params);

// The volume (m³) of a depth field on `terrain`'s cells: cell² · Σ depth, the measure every
// model's water volume uses.
double water_volume(const std::vector<float>& depth, const Heightmap& terrain);

}  // namespace runnel
