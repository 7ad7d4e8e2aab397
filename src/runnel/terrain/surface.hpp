// SPDX-License-Identifier: MIT
#pragma once
#include "runnel/core/heightmap.hpp"

namespace runnel {

// The height of the terrain's triangle mesh at (x, z) in metres: the C++ reference of
// cl/terrain_sample.cl (tiles split along (i, j)–(i+1, j+1)); points outside are clamped.
double surface_height(const Heightmap& terrain, double x, double z);

}  // namespace runnel
