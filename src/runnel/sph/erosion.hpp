// SPDX-License-Identifier: MIT
#pragma once
#include <string>

#include "runnel/compute/context.hpp"
#include "runnel/io/json.hpp"
#include "runnel/sim/parameters.hpp"
#include "runnel/sph/sph_solver.hpp"

namespace runnel {

// The erosion of one run, resolved from the erosion.* parameters.
struct ErosionSettings {
  std::string model = "capacity";  // or "acidity"
  double capacity = 0.2;           // K_c, s/m
  double erode_rate = 0.005;       // K_s, 1/s
  double deposit_rate = 0.005;     // K_d, 1/s
  double min_slope_deg = 2;
  double time_scale = 5000;
  double contact_distance = 0.5;  // m (resolved from dx)
  double limit_fraction = 0.5;
  double acidity = 0.001;  // m
  long long capacity_contacts = 10;
  double deposit_fraction = 1.0;
  double height_quantum = 1e-6;    // m
  double depth_exponent = 1.0;     // β: capacity × (flow depth in layers)^β
  double layer_neighbours = 17.1;  // neighbours of a particle in one flat layer

  static ErosionSettings from(const Parameters& p, double spacing);
  // OpenCL build options (-DEROSION_...) for cl/erode.cl.
  std::string build_options(double particle_volume, double volume_quantum) const;
  JsonObject json() const;
};

// Host side of cl/erode.cl: each particle's exchange with the terrain and its evaporation,
// accumulated into the terrain's fixed-point deltas (applied once per step by DeviceTerrain).
class Erosion {
 public:
  Erosion(ComputeContext& compute, const ErosionSettings& settings, const SphSolver& solver);
  void exchange(SphSolver& solver, double dt);
  const ErosionSettings& settings() const { return settings_; }

 private:
  ComputeContext& compute_;
  ErosionSettings settings_;
  cl::Kernel kernel_;
};

}  // namespace runnel
