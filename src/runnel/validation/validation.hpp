// SPDX-License-Identifier: MIT
#pragma once
#include <string>
#include <vector>

#include "runnel/compute/context.hpp"
#include "runnel/io/json.hpp"
#include "runnel/sim/parameters.hpp"

namespace runnel {

// The SPH reference cases (physics.md §5): `runnel validate CASE`.
struct ValidationOptions {
  int resolution = 0;     // particles across the case's length scale; 0: the case's default
  std::string out_dir;    // where CSVs go; empty: none
  Parameters params;      // sph.* overrides (--set)
  bool progress = false;  // progress lines on stderr
};

struct ValidationResult {
  std::string name;
  long long particles = 0;
  long long steps = 0;
  double wall_seconds = 0;
  double relative_error = 0;
  double target = 0;  // the acceptance threshold for relative_error
  JsonObject details;
  std::string summary_json() const;
};

// A water column of height H settles in a closed box; pressure against ρ0·g·d below the top three
// layers.
ValidationResult validate_hydrostatic(ComputeContext& compute, const ValidationOptions& options);
// A column L wide and 2L high collapses in a tank 4L long; surge front against Koshizuka & Oka
// 1996.
ValidationResult validate_dambreak(ComputeContext& compute, const ValidationOptions& options);

// The Koshizuka & Oka (1996) surge-front measurements: t* = t·sqrt(g/L), x/L.
struct FrontSample {
  double t_star;
  double x_over_l;
};
const std::vector<FrontSample>& koshizuka_oka_1996();

}  // namespace runnel
