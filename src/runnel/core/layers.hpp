// SPDX-License-Identifier: MIT
#pragma once
#include <string>
#include <vector>

#include "runnel/core/parameters.hpp"

namespace runnel {

// The keys of one [[layers]] entry, declared once (name, type, default, unit, range, meaning):
// the scenario reader validates against them and docs/parameters.md lists them.
const std::vector<ParamSpec>& layer_table();

// A layer's value for `key`: the one it sets, else the table's default.
ParamValue layer_value(const LayerValues& layer, const std::string& key);
double layer_real(const LayerValues& layer, const std::string& key);
std::string layer_text(const LayerValues& layer, const std::string& key);

// How a stratum's lower boundary is given: a thickness (constant, with noise, or from a raster)
// below the stratum above it, or an absolute dipping plane (a contact, as in Landlab's
// LithoLayers).
enum class LayerShape { kConstant, kNoise, kRaster, kDipping };
LayerShape layer_shape(const LayerValues& layer);

// The [[layers]] section of docs/parameters.md.
std::string layers_markdown();

}  // namespace runnel
