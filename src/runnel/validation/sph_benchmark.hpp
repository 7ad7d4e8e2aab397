// SPDX-License-Identifier: MIT
#pragma once
#include "runnel/compute/context.hpp"
#include "runnel/io/json.hpp"
#include "runnel/sim/parameters.hpp"

namespace runnel {

// `runnel bench sph`: a block of N particles settling under gravity in a closed tank, timed over
// S steps after a warm-up, with per-kernel times from OpenCL profiling events.
JsonObject benchmark_sph(ComputeContext& compute, long long particles, int steps,
                         const Parameters& params);

// `runnel bench droplet`: batches of Beyer droplets on an fBm terrain of size × size vertices.
JsonObject benchmark_droplet(ComputeContext& compute, int size, int batches,
                             const Parameters& params);
// `runnel bench olsen`: iterations of Olsen's cellular automaton on a size × size terrain.
JsonObject benchmark_olsen(ComputeContext& compute, int size, int iterations,
                           const Parameters& params);
// `runnel bench thermal`: talus relaxation passes on a size × size terrain.
JsonObject benchmark_thermal(ComputeContext& compute, int size, int iterations,
                             const Parameters& params);
// `runnel bench pipe`: adaptive steps of the virtual-pipe model on a size × size terrain.
JsonObject benchmark_pipe(ComputeContext& compute, int size, int steps, const Parameters& params);

}  // namespace runnel
