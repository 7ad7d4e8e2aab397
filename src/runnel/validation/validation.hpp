// SPDX-License-Identifier: MIT
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "runnel/compute/context.hpp"
#include "runnel/core/heightmap.hpp"
#include "runnel/core/parameters.hpp"
#include "runnel/io/json.hpp"
#include "runnel/models/parameter_table.hpp"

namespace runnel {

// The SPH reference cases (physics.md §5): `runnel validate CASE`.
struct ValidationOptions {
  int resolution = 0;   // particles across the case's length scale; 0: the case's default
  std::string out_dir;  // where CSVs go; empty: none
  Parameters params = default_parameters();  // parameter overrides (--set)
  bool progress = false;                     // progress lines on stderr
  double settle_time = 0;    // s, hydrostatic: how long the column settles; 0: the case's default
  Heightmap terrain;         // erosion-convergence: the terrain; empty: fBm hills
  std::string terrain_name;  // how the summary names `terrain` (its file)
};

struct ValidationResult {
  std::string name;
  long long particles = 0;
  long long steps = 0;
  double wall_seconds = 0;
  double relative_error = 0;
  double target = 0;              // the acceptance threshold for relative_error
  bool other_targets_met = true;  // the case's further targets, each reported in details
  JsonObject details;
  JsonObject summary() const;
  std::string summary_json() const { return summary().str(); }
};

// A water column of height H settles in a closed box: each layer's pressure against ρ0·g·d (the
// worst within 3 %) and the water's compression at rest (within 0.1 % on average).
ValidationResult validate_hydrostatic(ComputeContext& compute, const ValidationOptions& options);
// A column L wide and 2L high collapses in a tank 4L long: the surge front against a converged
// instant release (within 5 % on average) and Koshizuka & Oka 1996 (within 10 % from t* = 1.4 on).
ValidationResult validate_dambreak(ComputeContext& compute, const ValidationOptions& options);

// Erosion against numerical knobs: half the time step, half the particle size (same rain volume),
// spawn heights of 0.5 and 2 spacings, twice the speed of sound, each against the base run
// (resolution: vertices per side of the fBm hills, default 65, unless `terrain` is given;
// settle_time: the simulated seconds, default 20).
ValidationResult validate_erosion_convergence(ComputeContext& compute,
                                              const ValidationOptions& options);

// Lone droplets on the terrain: bounce (no energy gained, rebound e²), slide (g sin α, Manning's
// terminal speed) and resting clearance against spawn height.
ValidationResult validate_droplet(ComputeContext& compute, const ValidationOptions& options);

// One droplet released at rest 2 m above flat ground, followed for 10 s (heights in m above the
// ground; the contact surface is contact_height above it).
struct BounceResult {
  double cfl = 0, restitution = 0;
  double release_height = 0, contact_height = 0;
  double highest_after_landing = 0;  // the highest point after the first contact
  double first_rebound = -1;         // the apex of the first rebound
  long long steps = 0;
};
BounceResult droplet_bounce(ComputeContext& compute, const Parameters& params, double cfl,
                            double restitution);

// One droplet sliding from rest down a 20° plane for 3 s.
struct SlideResult {
  double cfl = 0, manning_n = 0, slope_deg = 0, duration = 0;
  double acceleration = 0, expected_acceleration = 0;  // fitted, and g sin α (m/s²)
  double speed = 0, expected_speed = 0;                // at the end (m/s)
  long long steps = 0;
};
SlideResult droplet_slide(ComputeContext& compute, const Parameters& params, double cfl,
                          double manning_n);

// The height above flat ground (m) at which a droplet spawned `spawn_height` above it rests after
// 2 s.
double droplet_rest_clearance(ComputeContext& compute, const Parameters& params,
                              double spawn_height);

// The Koshizuka & Oka (1996) surge-front measurements: t* = t·sqrt(g/L), x/L.
struct FrontSample {
  double t_star;
  double x_over_l;
};
const std::vector<FrontSample>& koshizuka_oka_1996();

// Other readings of dam-break fronts than the target's, scored beside it (no target of their own):
// Koshizuka & Oka's experiment read from its figure a second time, and Martin & Moyce's (1952)
// two columns of the same shape. The same values as data/reference/dambreak_other_readings.csv.
struct FrontReading {
  std::string name;    // its key in the JSON
  std::string source;  // the experiment, and who read it from the figure
  std::vector<FrontSample> samples;
};
const std::vector<FrontReading>& dambreak_other_readings();

// The same instant release solved by another code (PySPH's own dam-break example, finer than
// runnel's default): not a measurement but a check that runnel solves the case as posed. Scored
// like a reading, its "error" is the gap between the two codes' surge distances. The same values as
// data/reference/dambreak_pysph_instant_release.csv.
const FrontReading& dambreak_instant_release();

// A simulated front, (t*, x/L) in time order, against measurements, on the surge distance x − L:
// error = |s_sim − s_exp| / s_exp at each measured time inside the simulated times whose front lies
// inside the tank (1 < x_exp < tank_length, in L) and so could be reached; the front between two
// samples is interpolated linearly.
struct SurgeComparison {
  double t_star, x_experiment, x_simulated, error;
};
struct SurgeScore {
  std::vector<SurgeComparison> points;
  double mean = 0, worst = 0;
};
SurgeScore score_surge_front(const std::vector<std::pair<double, double>>& front,
                             const std::vector<FrontSample>& measured, double tank_length);

}  // namespace runnel
