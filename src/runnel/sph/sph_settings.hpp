// SPDX-License-Identifier: MIT
#pragma once
#include <string>

#include "runnel/sim/parameters.hpp"

namespace runnel {

struct SphSettings;
// The radius (m) over which a particle's water is counted on the terrain and its erosion spread
// (cl/footprint.cl): at least the kernel's support 2h and 2 cells, at most 8 cells.
double footprint_radius(const SphSettings& s, double terrain_cell);

// The SPH parameters of one run, resolved: no "auto" values left. Built from the parameter table.
struct SphSettings {
  double spacing = 0.1;  // dx, m
  double h = 0.12;       // smoothing length, m
  double rho0 = 1000.0;  // kg/m³
  double c0 = 20.0;      // m/s
  double alpha_visc = 0.02;
  double delta = 0.1;
  double cfl = 0.25;
  double dt_min = 1e-7;   // s
  double dt_max = 1e-2;   // s
  double gravity = 9.81;  // m/s²
  double restitution = 0.0;
  double manning_n = 0.03;       // s/m^(1/3), bed friction of the terrain contact
  double contact_radius = 0.05;  // m: a particle touches the terrain with its lowest point
  double surface_eps = 0.001;    // m
  double density_min = 0.5;      // × ρ0
  double density_max = 1.5;      // × ρ0
  bool clamp_negative_pressure = true;
  bool walls = false;

  double mass() const { return rho0 * spacing * spacing * spacing; }  // kg
  double tait_b() const { return c0 * c0 * rho0 / 7.0; }              // Pa

  // `default_spacing` and `reference_speed` fill sph.spacing = 0 and sph.c0 = 0 (c0 = 10 v_ref).
  static SphSettings from(const Parameters& params, double default_spacing, double reference_speed);
  // OpenCL build options carrying the constants into the kernels (exact float values).
  std::string build_options() const;
};

}  // namespace runnel
