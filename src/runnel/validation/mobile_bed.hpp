// SPDX-License-Identifier: MIT
#pragma once
#include <string>
#include <vector>

#include "runnel/core/heightmap.hpp"
#include "runnel/validation/soares_frazao_2012.hpp"
#include "runnel/validation/validation.hpp"

namespace runnel {

// The flume of Soares-Frazão et al. (2012) on a grid of `cell` metres (docs/validation.md,
// "Dam break over a mobile bed"): a channel 3.6 m wide with a fixed floor at 0, the upstream tank
// 9.2 m wide and 0.1 m deeper (as PyExner models it), two blocks leaving a 1 m gate at x = ±0.5,
// 85 mm of sand from x = −1 to 9 m ending on a fixed sill, walls 1 m high around it all, the
// outlet open at x = 15.5 m. Map coordinates: x from the gate's centre, y from the axis.
struct Flume {
  Heightmap terrain;         // the floor with the sand on it, the walls
  std::vector<float> sand;   // the sand's thickness per vertex (m): the [[layers]] stratum
  std::vector<float> walls;  // 1 where the ground is frozen (walls, blocks, sill), else 0
};
Flume soares_frazao_flume(double cell);

// Writes the flume as a scenario `runnel run` and `runnel compare --models pipe,sph` take:
// terrain.asc, sand.npy and walls.npy into `data_dir`, and at `scenario_path` the scenario that
// names them (relative to its folder): the pipe model's godunov flux and bed-load law, the
// reservoir as a [[water.bodies]], the gauges and their mirror images as [[probes]].
void write_flume_scenario(const Flume& flume, const std::string& data_dir,
                          const std::string& scenario_path);

// How far a simulated value lies outside the band [low, high] of the experiment's repeats (0
// inside it).
double outside_band(double value, double low, double high);

// The case: the scenario written into out_dir/flume (a temporary folder without --out), run to
// 20 s with the pipe model, or the model --set run.model names (resolution: cells a metre,
// default 20), scored against the gauges (water-surface RMSE and arrival, mirrored pairs
// averaged) and the final bed along the three profiles (RMSE and worst error against the band of
// the four repeats, scour below the gate, the deposit's crest); gauges.csv, profiles.csv and the
// run's own outputs in out_dir.
ValidationResult validate_mobile_bed(ComputeContext& compute, const ValidationOptions& options);

}  // namespace runnel
