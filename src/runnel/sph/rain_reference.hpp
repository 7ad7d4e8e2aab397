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
  double vy;        // m/s
  double age;       // s: how long it has fallen since its time within the step
};

// The drops cl/rain.cl spawns in slots first_counter … first_counter + count − 1 of the run's
// seed, in plain C++ and double precision (the random numbers are the host's rng_uniform, bit for
// bit the device's): the oracle of rain_emit. `spread` is the step the drops are spread over (0:
// all at its end), `gravity` what they fall under meanwhile. With rain.above_water the spawn
// height is above the terrain plus `water_depth` (m on the terrain's vertices, row-major;
// interpolated bilinearly in each cell).
std::vector<Drop> emit(const RainSettings& rain, double contact_radius, double surface_eps,
                       const Heightmap& terrain, std::uint64_t seed, std::uint64_t first_counter,
                       std::size_t count, double spread = 0.0, double gravity = 0.0,
                       const std::vector<double>& water_depth = {});

}  // namespace runnel::rain_reference
