// SPDX-License-Identifier: MIT
#pragma once
#include <string>
#include <vector>

#include "runnel/compute/context.hpp"
#include "runnel/core/parameters.hpp"
#include "runnel/io/json.hpp"
#include "runnel/models/parameter_table.hpp"
#include "runnel/validation/kinematic_wave.hpp"

namespace runnel {

// `runnel validate overland`: rain on a walled plane with an open foot, every model that moves
// water against the kinematic wave (kinematic_wave.hpp; docs/validation.md, "Overland flow").
struct OverlandCase {
  double length = 50;         // m, from the upstream wall to the open foot
  double width = 0.5;         // m between the side walls
  double slope = 0.2;         // m/m: supercritical at the foot, the sheet thin against the slope
  double manning_n = 0.1;     // s/m^(1/3), every model's
  double rain_mm_h = 120000;  // mm/h: a sheet 0.55 m deep at the foot, which SPH resolves at 0.1 m
  double duration = 0;        // s of rain; 0: 2 t_e
  double recession = 0;       // s run after the rain; 0: t_e
  double cell = 0.1;          // m, the terrain's grid (the grid models' cells)
  // m, SPH's particle spacings: two that run in 2–30 minutes on 2 cores (0.05 m takes hours)
  std::vector<double> spacings = {0.1, 0.07};
  // The runs: pipes, local-inertial, godunov (the pipe model's fluxes), wcsph, dfsph.
  std::vector<std::string> runs = {"pipes", "local-inertial", "godunov", "wcsph", "dfsph"};
  Parameters params = default_parameters();  // further overrides (--set)
  std::string out_dir;  // each run's outflow.csv, overland.json and the figure; empty: none
  bool progress = false;

  // The analytic plane the case is scored against (the rain in m/s, the duration resolved).
  KinematicPlane plane() const;
  // Refuses (input error, exit 2) a case outside the kinematic wave (k < 3), a spacing that puts
  // fewer than two particles in the depth at the foot, and unknown runs.
  void check() const;
};

// The names `runs` may hold.
const std::vector<std::string>& overland_run_names();

// Runs every run of the case (SPH ones once per spacing) and scores each: JSON with the
// analytic figures and one entry per run; the figure and the outflow.csv files in out_dir.
JsonObject validate_overland(ComputeContext& compute, const OverlandCase& c);

}  // namespace runnel
