// SPDX-License-Identifier: MIT
#pragma once
#include "runnel/core/heightmap.hpp"

namespace runnel {

// The height of the terrain's triangle mesh at (x, z) in metres: the C++ reference of
// cl/terrain_sample.cl (tiles split along (i, j)–(i+1, j+1)); points outside are clamped.
double surface_height(const Heightmap& terrain, double x, double z);

// The contact surface: the terrain with every vertex raised by radius / n_y (its normal's vertical
// part, at least 0.2), as cl/terrain_sample.cl's offset_surface builds it.
Heightmap contact_surface(const Heightmap& terrain, double radius);

}  // namespace runnel
