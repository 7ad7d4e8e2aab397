// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <string>

#include "runnel/compute/context.hpp"
#include "runnel/core/parameters.hpp"
#include "runnel/io/json.hpp"
#include "runnel/models/model.hpp"
#include "runnel/sim/hydrograph.hpp"

namespace runnel {

struct RunOptions {
  std::string out_dir;             // outputs; created if missing
  bool quiet = false;              // no progress on stderr
  std::uint64_t until_step = 0;    // run until this step count (absolute); 0: until until_time
  double until_time = 0;           // the model's clock: s, or iterations
  long long report_every = 200;    // steps between mass-balance reports
  long long checkpoint_every = 0;  // steps; 0: none (final.h5 is always written)
  int keep_checkpoints = 3;        // the newest K checkpoints are kept
  long long series_every = 0;      // steps between heightmap frames in series.h5; 0: none
  long long particles_every = 0;   // steps between SPH particle snapshots in series.h5; 0: none
  bool overwrite = false;          // replace checkpoints another run left in out_dir/checkpoints
  // The counters of the checkpoint a resumed run starts from: where outflow.csv's recorder was.
  std::vector<std::pair<std::string, std::int64_t>> resumed_counters;
};

struct RunSummary {
  std::uint64_t steps = 0;
  double sim_time = 0;
  double wall_seconds = 0;
  MassBalance balance;
  double rain_volume = 0;                                      // m³
  std::vector<std::pair<std::string, double>> terrain_values;  // metrics::terrain_metric_values
  JsonObject metrics;                                          // what metrics.json holds
  std::string caution;  // Model::caution() at the end, printed after the summary (empty: none)
  std::vector<std::pair<std::string, double>> model_values;  // Model::summary_values()
  std::vector<HydrographPoint> hydrograph;                   // outflow.csv's rows (t, outflow)
};

// Advances `model` to the target, reporting the mass balance every report_every steps, writing
// checkpoints and series frames as asked, then height_initial.png, height_final.png, erosion.png,
// final.asc, final.npy, final.h5 and metrics.json into the output folder.
RunSummary run_model(ComputeContext& compute, Model& model, const RunOptions& options);

// How long a run with `clock` lasts when run.steps is 0, in that clock: run.sim_time, or for a
// model in years run.sim_years when set.
double run_length_in_clock(const Parameters& params, ModelClock clock);
// The run options a parameter set asks for: run.steps, else run.sim_time (models with a clock in
// seconds), run.sim_years or run.sim_time (years) or run.iterations (iteration models);
// run.report_every.
RunOptions run_options_from(const Parameters& params, ModelClock clock);
// Throws an input error when the run has no length (run.steps, run.sim_time or run.iterations 0).
void require_run_length(const Parameters& params, ModelClock clock);

}  // namespace runnel
