// SPDX-License-Identifier: MIT
#pragma once
#include <filesystem>

#include "runnel/core/heightmap.hpp"
#include "runnel/ground/ground.hpp"
#include "runnel/io/json.hpp"

namespace runnel {

// A layered run's own outputs in `out`: geology.png (the exposed material, hillshaded, with a
// legend), exposed_layer.tif and .npy (the material index per vertex; the names are in
// metrics.json), sediment_thickness.tif (m). Returns metrics.json's "ground" entry.
JsonObject write_ground_outputs(const std::filesystem::path& out, Ground& ground,
                                const Heightmap& final_terrain);

}  // namespace runnel

namespace runnel {

// `runnel generate` of a layered scenario: the strata on the generated terrain, as one raster of
// thickness (m) per stratum beside `terrain_path` (STEM.NAME.EXT, in the terrain's format), or,
// when `terrain_path` ends in .h5, one HDF5 file with the terrain and the stack (docs/layers.md).
// Returns the files written.
std::vector<std::string> write_layered_terrain(const std::string& terrain_path,
                                               const Heightmap& terrain, const Strata& strata,
                                               double quantum);

}  // namespace runnel
