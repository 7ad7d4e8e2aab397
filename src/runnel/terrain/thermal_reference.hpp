// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <vector>

namespace runnel::thermal_reference {

// One talus pass of cl/thermal.cl (thermal_outflow, then thermal_gather) in plain C++ and double
// precision: the oracle the kernels are tested against. Heights are integer counts of the height
// quantum; `talus` is the threshold in quanta.
std::vector<std::int64_t> relax(const std::vector<std::int64_t>& height, int nx, int ny,
                                std::int64_t talus, double rate, bool height_aware,
                                double hardness);

}  // namespace runnel::thermal_reference
