// SPDX-License-Identifier: MIT
#pragma once
#include "runnel/core/heightmap.hpp"
#include "runnel/core/parameters.hpp"

namespace runnel {

// The terrain a scenario asks for: its file (terrain.file, read with terrain.nodata and
// terrain.cell_from_file), its graph (terrain.graph), or its generator (terrain.generator with
// terrain.set.*).
Heightmap load_terrain(const Parameters& params);

}  // namespace runnel
