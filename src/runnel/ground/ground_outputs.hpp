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
