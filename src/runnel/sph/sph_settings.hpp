// SPDX-License-Identifier: MIT
#pragma once
#include <string>

#include "runnel/core/parameters.hpp"

namespace runnel {

struct SphSettings;
// The particle spacing of a run on terrain cells of `terrain_cell` m: sph.spacing, or by default
// half a cell, so a channel a few cells wide is several particles across (docs/erosion.md).
double particle_spacing(const Parameters& params, double terrain_cell);
// The radius (m) over which a particle's water is counted on the terrain and its erosion spread
// (cl/footprint.cl): at least the kernel's support 2h and 2 cells, at most 8 cells.
double footprint_radius(const SphSettings& s, double terrain_cell);

// The SPH parameters of one run, resolved: no "auto" values left. The sph.* parameters fill it
// from their table (sph_settings.cpp: defaults, units, meaning); from() resolves the rest.
struct SphSettings {
  std::string solver;  // a registered pressure solver (pressure/registry.cpp, docs/sph.md)
  double spacing;      // dx, m
  double h_factor;
  double h;     // smoothing length h_factor · dx, m
  double rho0;  // kg/m³
  double c0;    // m/s
  double alpha_visc;
  double delta;
  double cfl;
  double cfl_flow;                // dfsph: dt = cfl_flow · dx / |v|max
  double dfsph_density_error;     // dfsph: mean density error the constant-density solve allows, %
  double dfsph_divergence_error;  // dfsph: mean compression per step the divergence solve allows, %
  int dfsph_max_iterations;       // dfsph: iterations of each solve at most
  bool dfsph_floor_images;        // dfsph: the terrain as mirror images, not its volume map
  bool contact_face_normal;       // the contact also clears the velocity into the hit face
  double dt_min;                  // s
  double dt_max;                  // s
  double gravity;                 // m/s²
  double restitution;
  double manning_n;       // s/m^(1/3), bed friction of the terrain contact
  double contact_radius;  // m (the parameter is in dx): a particle touches with its lowest point
  double surface_eps;     // m (the parameter is in dx)
  double density_min;     // × ρ0
  double density_max;     // × ρ0
  bool clamp_negative_pressure;
  bool walls;

  // Water at rest is at ρ0 with this solver (PressureMethod::incompressible).
  bool incompressible() const;
  double mass() const { return rho0 * spacing * spacing * spacing; }  // kg
  // The kernel summed over a cubic lattice of spacing dx, in particle volumes dx³: 1.0175 at
  // h = 1.2 dx. dfsph's summation density divides by it, so that water at rest at the spacing
  // it was made with is at ρ0 (docs/sph.md).
  double lattice_sum() const;
  double tait_b() const { return c0 * c0 * rho0 / 7.0; }  // Pa

  // `default_spacing` and `reference_speed` fill sph.spacing = 0 and sph.c0 = 0 (c0 = 10 v_ref).
  static SphSettings from(const Parameters& params, double default_spacing, double reference_speed);
  // OpenCL build options carrying the constants into the kernels (exact float values).
  std::string build_options() const;
};

}  // namespace runnel
