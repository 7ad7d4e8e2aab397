// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <vector>

#include "runnel/models/pipe_model.hpp"

namespace runnel::pipe_reference {

// The state of the virtual-pipe model: terrain and suspended sediment in height quanta; depth (m),
// fluxes (m³/s, L R T B per cell) and velocity (m/s, x z per cell) as doubles.
struct State {
  std::vector<std::int64_t> height, sediment;
  std::vector<double> depth, flux, velocity;
  std::int64_t outflow = 0;  // quanta that left the map
};

// One step of length dt of cl/models/pipe.cl (flux, water, erode, upwind transport) in plain C++
// and double precision, with the device's random numbers for the stochastic rounding: the oracle
// of the pipe kernels. `step_index` is the model's step count before the step.
void step(State& state, int nx, int ny, double cell, double quantum, const PipeSettings& settings,
          double dt, std::uint64_t seed, std::uint64_t step_index);

// The water of one step of length dt under pipe.flux = "godunov" (cl/models/pipe_godunov.cl: the
// bed's and depth's slopes, the faces, the update) in plain C++ and double precision: the depths,
// velocities and the faces' outflows (pipe_godunov_reference.cpp).
void godunov_water(State& state, int nx, int ny, double cell, double quantum,
                   const PipeSettings& settings, double dt);

}  // namespace runnel::pipe_reference
