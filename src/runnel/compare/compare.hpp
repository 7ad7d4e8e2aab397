// SPDX-License-Identifier: MIT
#pragma once
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "runnel/compute/context.hpp"
#include "runnel/core/heightmap.hpp"
#include "runnel/core/parameters.hpp"
#include "runnel/ground/strata.hpp"
#include "runnel/models/mass_balance.hpp"
#include "runnel/sim/hydrograph.hpp"

// runnel compare: several erosion models on one terrain with one rain budget (docs/models.md).
namespace runnel::compare {

// The water every model with rain receives: the SPH scenario's rain (rate × particle volume ×
// run.sim_time), and the particle volume a droplet stands for.
struct RainBudget {
  double volume = 0;           // m³
  double duration = 0;         // s (run.sim_time)
  double particle_volume = 0;  // m³ (the SPH particle spacing cubed)
  double sph_rate = 0;         // SPH particles/s
};
RainBudget rain_budget(ComputeContext& compute, const Parameters& params, const Heightmap& terrain);

// The parameters of `model` in the comparison: the scenario's, with its rain and run length set
// so that it receives the budget (pipe: pipe.rain over run.sim_time; olsen: olsen.rain over
// run.iterations; droplet: one droplet per SPH particle volume, run.iterations batches).
Parameters model_parameters(const Parameters& scenario, const std::string& model,
                            const RainBudget& budget, const Heightmap& terrain);

// One model's results, the rows of metrics.csv.
struct ModelResult {
  std::string model, class_name, clock, folder;
  std::string setup;    // the parameters compare set for the budget ("pipe.rain = 0.02")
  std::string caution;  // what limits the trust in this model's result (Model::caution)
  unsigned long long steps = 0;
  double time = 0, wall_seconds = 0, rain_volume = 0;
  MassBalance balance;
  std::vector<std::pair<std::string, double>> terrain_values;
  Heightmap final_terrain;
  Heightmap erosion_reference;  // what its erosion map is measured from (Model::erosion_reference)
  // A layered run (docs/layers.md): its strata, the material exposed at each vertex at the end,
  // and the rock eroded from each material (m³; the strata, then the bedrock).
  std::optional<Strata> strata;
  std::vector<int> exposed;
  std::vector<double> eroded_per_material;
  // Its outflow.csv's rows (t, outflow m³/s), for the models whose clock is in seconds (empty
  // else).
  std::vector<HydrographPoint> hydrograph;
};

struct Options {
  std::vector<std::string> models;
  std::string out_dir;
  std::string scenario_name;  // for the report's title
  bool quiet = false;
};

// Runs every model into OUT/MODEL (as runnel run), then writes OUT/metrics.csv, OUT/compare.png and
// OUT/report.md. Every parameter set is built and checked before anything runs or is written.
std::vector<ModelResult> run_compare(ComputeContext& compute, const Parameters& scenario,
                                     const Heightmap& terrain, const Options& options);

// metrics.csv: a header, then a row per model.
std::string metrics_csv(const std::vector<ModelResult>& results);
// compare.png: the initial terrain, then each model's final terrain above its erosion map, all
// with one height range and one Δh colour scale.
void write_compare_png(const std::string& path, const Heightmap& initial,
                       const std::vector<ModelResult>& results);
// report.md: the figure, the budget and the table.
std::string report_markdown(const std::vector<ModelResult>& results, const RainBudget& budget,
                            const Heightmap& initial, const Options& options);

}  // namespace runnel::compare
