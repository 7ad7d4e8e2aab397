// SPDX-License-Identifier: MIT
#pragma once
#include <string>

#include "runnel/compute/context.hpp"
#include "runnel/io/json.hpp"
#include "runnel/sim/parameters.hpp"
#include "runnel/sim/simulation.hpp"

namespace runnel {

struct RunOptions {
  std::string out_dir;  // outputs; created if missing
  bool quiet = false;   // no progress on stderr
};

struct RunSummary {
  std::uint64_t steps = 0;
  double sim_time = 0;
  double wall_seconds = 0;
  MassBalance balance;
  JsonObject metrics;  // what metrics.json holds
};

// `runnel run`: advances a simulation for run.steps steps (or run.sim_time seconds), reporting the
// mass balance every run.report_every steps, and writes height_initial.png, height_final.png,
// erosion.png, final.asc, final.npy and metrics.json into the output folder.
RunSummary run_simulation(ComputeContext& compute, const Parameters& params,
                          const Heightmap& terrain, const RunOptions& options);

}  // namespace runnel
