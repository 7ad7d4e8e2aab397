// SPDX-License-Identifier: MIT
#pragma once
#include <string>

#include "runnel/core/parameters.hpp"

namespace runnel {

// The ground.* parameters: the bedrock and the loose sediment (the two layers every layered
// terrain has) and the mask rasters (docs/layers.md). Their defaults, units and meaning: the table
// in ground_settings.cpp.
struct GroundSettings {
  std::string bedrock_name;
  double bedrock_erodibility, bedrock_talus_angle, bedrock_density;
  double sediment_erodibility, sediment_talus_angle, sediment_density;
  double active_layer;  // m
  std::string hardness_mask, rain_mask, frozen_mask;
  static GroundSettings from(const Parameters& params);
};

// Whether the run has a layer stack to keep: strata, or a hardness or frozen mask. Without one
// every model erodes one homogeneous material, exactly as it did before layers existed.
bool has_ground(const Parameters& params);
// Whether rain falls by a rain mask.
bool has_rain_mask(const Parameters& params);
// -DGROUND and -DRAIN_MASK for the kernels that read the erodibility and rain-weight fields
// (cl/common.cl): 0 compiles the reads away.
std::string ground_defines(const Parameters& params);

}  // namespace runnel
