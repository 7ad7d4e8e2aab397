// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <vector>

#include "runnel/models/olsen_model.hpp"

namespace runnel::olsen_reference {

// The state of Olsen 2004's automaton: terrain and suspended sediment in height quanta, water in m.
struct State {
  std::vector<std::int64_t> height, sediment;
  std::vector<double> water;
};

// One iteration of cl/models/olsen.cl (dissolve, outflow, gather, settle) in plain C++ and double
// precision: the oracle the kernels are tested against.
void iterate(State& state, int nx, int ny, const OlsenSettings& settings, double quantum);

}  // namespace runnel::olsen_reference
