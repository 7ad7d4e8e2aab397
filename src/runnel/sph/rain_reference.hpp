// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <vector>

#include "runnel/core/heightmap.hpp"
#include "runnel/sph/rain_emitter.hpp"

namespace runnel::rain_reference {

struct Drop {
  double x, y, z;   // m
  double lifespan;  // s
};

// The drops cl/rain.cl spawns in slots first_counter … first_counter + count − 1 of the run's
// seed, in plain C++ and double precision (the random numbers are the host's rng_uniform, bit for
// bit the device's): the oracle of rain_emit.
std::vector<Drop> emit(const RainSettings& rain, double contact_radius, double surface_eps,
                       const Heightmap& terrain, std::uint64_t seed, std::uint64_t first_counter,
                       std::size_t count);

}  // namespace runnel::rain_reference
