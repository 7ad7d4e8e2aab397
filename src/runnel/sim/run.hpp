// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <string>

#include "runnel/compute/context.hpp"
#include "runnel/io/json.hpp"
#include "runnel/sim/parameters.hpp"
#include "runnel/sim/simulation.hpp"

namespace runnel {

struct RunOptions {
  std::string out_dir;             // outputs; created if missing
  bool quiet = false;              // no progress on stderr
  std::uint64_t until_step = 0;    // run until this step count (absolute); 0: until until_time
  double until_time = 0;           // s, simulated
  long long report_every = 200;    // steps between mass-balance reports
  long long checkpoint_every = 0;  // steps; 0: none (final.h5 is always written)
  int keep_checkpoints = 3;        // the newest K checkpoints are kept
  long long series_every = 0;      // steps between heightmap frames in series.h5; 0: none
};

struct RunSummary {
  std::uint64_t steps = 0;
  double sim_time = 0;
  double wall_seconds = 0;
  MassBalance balance;
  JsonObject metrics;  // what metrics.json holds
};

// Advances `sim` to the target, reporting the mass balance every report_every steps, writing
// checkpoints and series frames as asked, then height_initial.png, height_final.png, erosion.png,
// final.asc, final.npy, final.h5 and metrics.json into the output folder.
RunSummary run_simulation(ComputeContext& compute, Simulation& sim, const RunOptions& options);

// The run options a parameter set asks for (run.steps or run.sim_time, run.report_every).
RunOptions run_options_from(const Parameters& params);

}  // namespace runnel
