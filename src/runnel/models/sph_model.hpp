// SPDX-License-Identifier: MIT
#pragma once
#include <memory>
#include <optional>

#include "runnel/models/model.hpp"
#include "runnel/models/sph_simulation.hpp"
#include "runnel/sph/water_resolution.hpp"

namespace runnel {

// Erosion_Runnel: runnel's own SPH rain erosion (physics.md), the Simulation behind the common
// model interface. Its particle fields are those of ParticleStore (particle__* in the dictionary).
class SphModel final : public Model, public Interactive {
 public:
  static const ModelInfo& model_info();
  SphModel(ComputeContext& compute, const Parameters& params, const Heightmap& terrain);
  explicit SphModel(std::unique_ptr<Simulation> simulation);
  const ModelInfo& info() const override { return model_info(); }

  double step() override;
  double time() const override { return sim_->time(); }
  double step_size() const override { return sim_->dt(); }
  void limit_next_step(double most) override { sim_->solver().limit_dt(most); }
  std::uint64_t steps() const override { return sim_->steps(); }
  const Parameters& parameters() const override { return sim_->parameters(); }
  Heightmap terrain() override { return sim_->terrain(); }
  const Heightmap& initial_terrain() const override { return sim_->initial_terrain(); }
  MassBalance mass_balance() override { return sim_->mass_balance(); }
  std::vector<double> elevation() override { return sim_->elevation(); }
  void set_elevation(const std::vector<double>& metres) override { sim_->set_elevation(metres); }
  Heightmap erosion_reference() override { return sim_->erosion_reference(); }
  double rain_rate() override { return sim_->rain_rate(); }
  void set_rain_rates(const std::vector<float>& metres_per_second) override {
    sim_->set_rain_rates(metres_per_second);
  }
  double rain_volume() override;
  double initial_water_volume() const override { return sim_->initial_water_volume(); }
  // Each particle stands for spacing³ of water: rain as spawned, outflow as the particles that left
  // over an open edge, stored as those alive (the edges are not told apart).
  std::optional<WaterBudget> water_budget() override;
  CheckpointData checkpoint() override { return sim_->checkpoint(); }
  void restore(const CheckpointData& data) override;
  JsonObject diagnostics() override;
  std::string caution() override;
  // The drops rain.max_particles held back, as a caution ("" when none were).
  std::string rain_caution();
  // A terrain whose scale the particle spacing cannot resolve: fewer than
  // kFewestDropsPerMinute drops a minute of rain, or particles larger than a quarter of the relief.
  std::string scale_caution() const;
  static constexpr double kFewestDropsPerMinute = 36;
  static constexpr double kMostSpacingPerRelief = 0.25;
  std::vector<std::pair<std::string, double>> summary_values() override;
  std::string status() override;
  double step_work() override { return static_cast<double>(sim_->particles()); }
  const char* work_unit() const override { return "particle_steps"; }
  double device_bytes() const override { return sim_->device_bytes(); }
  Ground* ground() override { return sim_->ground(); }
  // Painting: the emitter has one region, so the first disc that rains rains in place of the
  // scenario's rain; over a sink the particles evaporate; water_view() bins the particles onto the
  // vertices.
  Interactive* interactive() override { return this; }
  bool paints_rain() const override { return true; }
  void set_painted_rain(const std::vector<RainDisc>& discs) override;
  bool set_global_rain(bool on) override;
  WaterView water_view() override;
  bool paint_rain_mask(const std::vector<int>& vertices, float value) override;
  bool has_rain_mask() const override { return sim_->has_rain_mask(); }

  Simulation& simulation() { return *sim_; }

  // The particles as they are, their size, the rain spawned and its settings (water_view(),
  // the erosion-convergence validation, runnel compare's rain budget).
  HostParticles particles() { return sim_->solver().particles().download(); }
  std::uint64_t drops_spawned() { return sim_->rain().spawned(); }
  double particle_spacing() const { return sim_->solver().settings().spacing; }
  double sound_speed() const { return sim_->solver().settings().c0; }
  double volume_quantum() { return sim_->solver().terrain().volume_quantum(); }
  const RainSettings& rain() { return sim_->rain().settings(); }
  // How well the particles on the bed resolve the water there, now (water_resolution.hpp); measured
  // once per step, however many of metrics.json, the caution and a sweep ask.
  WaterResolution water_resolution();

 private:
  // The emitter's settings from the scenario's rain, the painted disc and the switch.
  void apply_rain();
  void drain_sinks();
  std::unique_ptr<Simulation> sim_;
  std::optional<std::pair<std::uint64_t, WaterResolution>> resolution_;  // (step, figure)
  RainSettings scenario_rain_;
  std::vector<RainDisc> painted_;
  bool global_rain_ = true;
};

}  // namespace runnel
