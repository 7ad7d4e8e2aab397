// SPDX-License-Identifier: MIT
#pragma once
#include <string>
#include <vector>

#include "runnel/core/heightmap.hpp"
#include "runnel/ground/strata.hpp"
#include "runnel/io/images.hpp"

namespace runnel {

// A geological map: each vertex coloured by its exposed material (index as in Strata), shaded by
// the terrain's hillshade, with a legend of the materials and their exposed shares beneath.
RgbImage geology_picture(const Strata& strata, const std::vector<int>& exposed,
                         const Heightmap& terrain);

// The colour of material `m` of `strata` (a fixed palette: the strata in order, then the bedrock
// and the sediment in colours of their own).
void material_colour(const Strata& strata, int m, std::uint8_t rgb[3]);

}  // namespace runnel
