// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <vector>

#include "runnel/core/heightmap.hpp"
#include "runnel/sph/erosion.hpp"
#include "runnel/sph/particle_store.hpp"

namespace runnel::erosion_reference {

struct Exchange {
  std::vector<std::int32_t> sediment;  // each particle's load after the step, volume quanta
  std::vector<std::uint32_t> id;       // with the dead flag of the evaporated
  std::vector<std::int64_t> delta;     // per vertex, height quanta (+ deposited, − eroded)
  std::int64_t lost = 0, evaporated = 0;
};

// The exchange of cl/erode.cl (stream-power or acidity model, evaporation, footprint spreading by
// systematic sampling) for every particle over a step dt, in plain C++ and double precision with
// the device's random numbers: the oracle of erode_exchange. `depth` is each particle's water depth
// on the bed (m).
Exchange exchange(const HostParticles& particles, const std::vector<float>& depth,
                  const Heightmap& terrain, const SphSettings& sph, const ErosionSettings& erosion,
                  double volume_quantum, double dt, std::uint64_t seed, std::uint64_t step_index);

}  // namespace runnel::erosion_reference
