// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "runnel/compute/context.hpp"
#include "runnel/core/heightmap.hpp"
#include "runnel/core/parameters.hpp"
#include "runnel/ground/ground.hpp"
#include "runnel/ground/rain_mask.hpp"
#include "runnel/io/json.hpp"
#include "runnel/models/checkpoint.hpp"
#include "runnel/models/imposed_change.hpp"
#include "runnel/models/mass_balance.hpp"
#include "runnel/sph/erosion.hpp"
#include "runnel/sph/rain_emitter.hpp"
#include "runnel/sph/sph_solver.hpp"
#include "runnel/terrain/thermal.hpp"

namespace runnel {

// One SPH rain-erosion run: the terrain, the fluid, the rain, erosion and talus, advanced together.
// Defaults that depend on the terrain (particle spacing, rain, spawn height, c0) are derived here
// from its cell size and relief (docs/erosion.md).
// The smallest terrain (vertices per side) the SPH model runs on.
inline constexpr int kMinSphVertices = 16;

class Simulation {
 public:
  Simulation(ComputeContext& compute, const Parameters& params, const Heightmap& terrain);

  // One step: kick → sph_continuity → drift + collide → erode.exchange → terrain.apply →
  // (thermal) → rain.emit → hash → sph_forces → kick.
  void step();

  MassBalance mass_balance();
  // Model::elevation() and set_elevation(): new heights put the particles they rose under back
  // on the surface.
  std::vector<double> elevation();
  void set_elevation(const std::vector<double>& metres);
  // Model::rain_rate() and set_rain_rates(): the scenario's rain spread over the whole terrain.
  double rain_rate() const;
  void set_rain_rates(const std::vector<float>& metres_per_second);
  // The initial terrain raised by the heights imposed so far (Model::erosion_reference).
  Heightmap erosion_reference() const;
  // The rain mask painted (runnel-viewer) on these vertices; false without ground.rain_mask.
  bool paint_rain_mask(const std::vector<int>& vertices, float value);
  bool has_rain_mask() const { return rain_mask_.present(); }
  Heightmap terrain();
  const Heightmap& initial_terrain() const { return initial_; }
  // The standing water's particles at t = 0 ([[water.bodies]], water.depth), m³.
  double initial_water_volume() const { return initial_water_volume_; }
  double time() const { return solver_->time(); }
  double dt() const { return solver_->dt(); }
  std::uint64_t steps() const { return solver_->steps(); }
  std::size_t particles() const { return solver_->particles().size(); }
  // The most device memory the run will hold (bytes), checked against the device when built.
  double device_bytes() const { return device_bytes_; }
  SphCounters counters() { return solver_->counters(); }
  const Parameters& parameters() const { return params_; }
  // The values the run actually uses, automatic ones resolved.
  JsonObject effective_settings() const;

  // The whole state for an exact restart, and back. restore() expects a Simulation built from the
  // checkpoint's parameters and initial terrain (make_model_from_checkpoint does both).
  CheckpointData checkpoint();
  void restore(const CheckpointData& data);

  SphSolver& solver() { return *solver_; }
  Ground* ground() { return ground_.get(); }
  RainEmitter& rain() { return *rain_; }
  const std::vector<std::int64_t>& initial_fixed() const { return initial_fixed_; }

 private:
  // device_bytes_ for the run's largest particle store, the terrain and the hash grid; a budget
  // that follows the storm is cut to what the device holds, a budget the user set is refused.
  void budget_device_memory(const ComputeContext& compute, const Heightmap& terrain,
                            RainSettings& rain, std::size_t standing_particles);
  ComputeContext& compute_;
  Parameters params_;
  Heightmap initial_;
  std::vector<std::int64_t> initial_fixed_;
  ImposedChange imposed_;  // heights a coupler set (set_elevation)
  double reference_speed_ = 0;
  std::unique_ptr<SphSolver> solver_;
  RainMask rain_mask_;  // ground.rain_mask, as painted
  std::unique_ptr<RainEmitter> rain_;
  std::unique_ptr<Erosion> erosion_;
  std::unique_ptr<ThermalRelaxation> thermal_;
  std::unique_ptr<Ground> ground_;
  double thermal_interval_ = 0;      // s
  double device_bytes_ = 0;          // see device_bytes()
  double initial_water_volume_ = 0;  // m³ of the standing water's particles at t = 0
};

}  // namespace runnel
