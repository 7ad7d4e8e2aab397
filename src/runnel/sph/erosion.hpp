// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <string>

#include "runnel/compute/context.hpp"
#include "runnel/compute/kernel.hpp"
#include "runnel/core/clock.hpp"
#include "runnel/core/parameters.hpp"
#include "runnel/ground/bedload.hpp"
#include "runnel/io/json.hpp"
#include "runnel/sph/sph_solver.hpp"
#include "runnel/terrain/bed_fields.hpp"

namespace runnel {

// The erosion of one run, resolved from the erosion.* parameters and the fluid's settings
// (docs/erosion.md): the stream-power model (Foster & Meyer 1975's coupling, Bagnold 1966's stream
// power) or Fritz 2016's acidity model.
struct ErosionSettings {
  // The erosion.* parameters (defaults, units, meaning: the table in erosion.cpp).
  std::string model;         // "stream-power", "acidity" or "bedload"
  double erodibility;        // K_ω, s²/m²
  double critical_power;     // ω_c, W/m²
  double transport;          // k_T, s²/m
  double settling;           // w_s, m/s
  double bed_density;        // ρ_b, kg/m³
  double max_concentration;  // c_max, bed volume per water volume
  double morphological_factor;
  double acidity;  // m
  std::int64_t capacity_contacts;
  double deposit_fraction;
  double height_quantum;     // m
  double exchange_interval;  // s; 0: every step
  // Resolved from the fluid and the terrain:
  double footprint_radius;    // m, where an exchange is spread
  SedimentSettings sediment;  // the grains, for the bed-load law

  static ErosionSettings from(const Parameters& p, const SphSettings& sph, double terrain_cell);
  // OpenCL build options (-DEROSION_...) for cl/erode.cl.
  std::string build_options(const SphSettings& sph, double volume_quantum) const;
  JsonObject json() const;
};

// Host side of cl/erode.cl: each particle's exchange with the terrain and its evaporation,
// accumulated into the terrain's fixed-point deltas (applied once per step by DeviceTerrain).
class Erosion {
 public:
  // With a ground, the detachment is scaled by the erodibility of the vertex under each particle.
  Erosion(ComputeContext& compute, const ErosionSettings& settings, const SphSolver& solver,
          std::uint64_t seed, const BedFields* bed = nullptr);
  // The exchange over the step of length dt that the solver has just drifted.
  void exchange(SphSolver& solver, double dt);
  // The time the step [time, time + dt] exchanges over: dt, or with erosion.exchange_interval the
  // interval at the steps that cross a multiple of it and 0 (no exchange) between.
  double exchange_time(double time, double dt) const {
    return interval_credit(settings_.exchange_interval, time, dt);
  }
  const ErosionSettings& settings() const { return settings_; }

 private:
  ErosionSettings settings_;
  std::uint64_t seed_;
  Kernel kernel_;
  cl::Buffer placeholder_;
};

}  // namespace runnel
