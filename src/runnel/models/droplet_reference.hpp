// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <vector>

#include "runnel/models/droplet_model.hpp"

namespace runnel::droplet_reference {

// One model step of cl/models/droplet.cl in plain C++ and double precision: a batch of `count`
// droplets (ids first_droplet …) moving in lockstep for their lifetime, the terrain's changes
// applied after every droplet step. `height` is in quanta and is updated; returns the quanta
// carried out of the map.
std::int64_t batch(std::vector<std::int64_t>& height, int nx, int ny, double quantum,
                   const DropletSettings& settings, std::uint64_t seed, std::uint64_t first_droplet,
                   std::size_t count);

}  // namespace runnel::droplet_reference
