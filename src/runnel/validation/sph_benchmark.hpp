// SPDX-License-Identifier: MIT
#pragma once
#include <string>

#include "runnel/compute/context.hpp"
#include "runnel/core/parameters.hpp"
#include "runnel/io/json.hpp"

namespace runnel {

// `runnel bench sph`: N particles in a closed tank, timed over S steps after a warm-up, with
// per-kernel times from OpenCL profiling events. scene "block": a block settling under gravity
// (the pressure solves' hardest case); "sheet": a film two particles deep running down a 10 %
// slope. `tile`: the neighbour passes' tile (SpatialHash), 0 for the device's.
JsonObject benchmark_sph(ComputeContext& compute, long long particles, int steps,
                         const Parameters& params, unsigned tile = 0,
                         const std::string& scene = "block");

// `runnel bench droplet|pipe|olsen|thermal`: `steps` steps of a registered model on an fBm
// terrain of size × size vertices after one warm-up step; cell_steps_per_second (or
// droplet_steps_per_second) and per-kernel times.
JsonObject benchmark_model(ComputeContext& compute, const std::string& name, int size, int steps,
                           Parameters params);

// `runnel bench generate`: every generator that runs on the device (the noise families) at
// size × size vertices, `steps` times each after a warm-up: vertices per second of the whole call
// (kernel and read-back) and of the kernel alone, per generator.
JsonObject benchmark_generators(ComputeContext& compute, int size, int steps);

}  // namespace runnel
