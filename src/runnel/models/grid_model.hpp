// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "runnel/compute/context.hpp"
#include "runnel/ground/ground.hpp"
#include "runnel/ground/rain_mask.hpp"
#include "runnel/models/grid_state.hpp"
#include "runnel/models/imposed_change.hpp"
#include "runnel/models/model.hpp"

namespace runnel {

// What every grid model (droplet, pipe, olsen, thermal) shares: the GridState, the clock, the mass
// balance (terrain change + suspended sediment + outflow, in quanta) and generic checkpoints (every
// field of the state plus the model's named counters). A model implements take_step() and, where
// it has them, its outflow and counters.
class GridModel : public Model, public Interactive {
 public:
  GridModel(ComputeContext& compute, const Parameters& params, const Heightmap& terrain);

  double step() final;
  double time() const final { return time_; }
  double step_size() const final { return next_dt(); }
  std::uint64_t steps() const final { return steps_; }
  const Parameters& parameters() const final { return params_; }
  Heightmap terrain() final;
  const Heightmap& initial_terrain() const final { return state_.initial_terrain(); }
  MassBalance mass_balance() final;
  std::vector<double> elevation() final;
  void set_elevation(const std::vector<double>& metres) final;
  // The rain of the models whose clock is in seconds (pipe); an iteration model's rain is no rate.
  double rain_rate() final {
    return info().clock == ModelClock::kSeconds ? scenario_rain_rate() : 0.0;
  }
  void set_rain_rates(const std::vector<float>& metres_per_second) final;
  Heightmap erosion_reference() final;
  double rain_volume() override { return painted_volume_; }
  double initial_water_volume() const override { return initial_water_volume_; }
  // Rain, edge outflow and the water standing now, for a model with a water depth field.
  std::optional<WaterBudget> water_budget() final;
  CheckpointData checkpoint() final;
  void restore(const CheckpointData& data) final;
  std::string status() override;
  double step_work() override { return static_cast<double>(state_.vertices()); }
  const char* work_unit() const override { return "cell_steps"; }
  // The state's fields and the terrain, the ground's layers, the rain weights and the model's own
  // buffers (scratch_bytes()).
  double device_bytes() const override;

  GridState& state() { return state_; }
  Ground* ground() final { return ground_.get(); }
  // Height quanta that left the map (outflow edges), and that the model has in suspension.
  virtual long long outflow_quanta() { return 0; }
  // m³ of water that has left the map over each edge (kEdgeNames' order); none where the edges are
  // closed.
  virtual std::array<double, 4> edge_water_outflow() { return {}; }
  // Height quanta a documented non-conserving option destroyed (negative: created).
  virtual long long lost_quanta() { return 0; }
  // Height quanta tectonic uplift added (stream-power), in all and per vertex (empty: none).
  virtual long long uplift_quanta() { return 0; }
  virtual std::vector<std::int64_t> uplift_per_vertex() { return {}; }
  virtual long long suspended_quanta();

  // Painting (interaction.hpp): models with a water depth field take painted rain as depth added
  // to the vertices of each disc after every step; the droplet model rains droplets in them.
  Interactive* interactive() override { return this; }
  bool paints_rain() const override;
  void set_painted_rain(const std::vector<RainDisc>& discs) override { painted_ = discs; }
  bool set_global_rain(bool on) override;
  WaterView water_view() override;
  bool paint_rain_mask(const std::vector<int>& vertices, float value) override;
  bool has_rain_mask() const override { return rain_mask_.present(); }

 protected:
  // One step of the numerics; returns its length in clock units.
  virtual double take_step() = 0;
  // How many steps may be queued on the device before step() waits for them.
  static constexpr std::uint64_t kStepsBetweenWaits = 64;
  // m³ of water standing on the terrain (surface_water__depth × cell²).
  double water_volume();
  // Fills the water depth field with the scenario's standing water (a model whose constructor
  // created that field calls it); returns whether there was any.
  bool start_standing_water(const Parameters& params);
  // Per-vertex state of the model's own beyond the state's fields, named "model__...", kept in
  // checkpoints.
  virtual void store_own_fields(std::vector<StoredField>&) {}
  virtual void restore_own_fields(const std::vector<StoredField>&) {}
  // Integer counters an exact restart needs, by name.
  virtual std::vector<std::pair<std::string, std::int64_t>> counters() { return {}; }
  virtual void restore_counters(const std::vector<std::pair<std::string, std::int64_t>>&) {}
  // Device bytes of the model's own buffers beyond the state's fields (buffer_bytes).
  virtual double scratch_bytes() const { return 0.0; }
  // The length of the next step where the model chooses it (pipe), saved for an exact restart.
  virtual double next_dt() const { return 1.0; }
  virtual void restore_next_dt(double) {}

  // Painted rain for a step of `dt` clock units (models with a water depth field), and sinks.
  virtual void paint(double dt);
  void drain(const std::vector<int>& vertices);
  const std::vector<RainDisc>& painted() const { return painted_; }
  // The scenario's rain as depth per clock unit on a vertex of weight 1 (pipe.rain, olsen.rain),
  // and the volume it has rained: rate × Σ weights × cell² × the time it was on, summed over the
  // stretches between rain-mask changes.
  virtual double scenario_rain_rate() const { return 0.0; }
  double scenario_rain_volume();
  // The rain weights on the device (and their sum) from the rain mask.
  void sync_rain_weights();
  // The scenario rain's switch as the kernels read it (1 or 0), and how long it has been on.
  float rain_on() const { return global_rain_ ? 1.0f : 0.0f; }
  double rain_time() const { return rain_time_; }
  // m³ of painted water so far, and the fraction of a droplet or particle painting carries over.
  double initial_water_volume_ = 0;
  ImposedChange imposed_;  // heights a coupler set (set_elevation)
  double painted_volume_ = 0, paint_carry_ = 0;
  // The scenario rain's volume before the last rain-mask change, and the rain time then.
  double rain_accum_ = 0, rain_mark_ = 0;

  // The ground's fields and the rain weights the model's kernels read (bed() is null, and the rain
  // weights a placeholder, when the run has none: the kernels then never read them).
  const BedFields* bed() const { return ground_ ? &ground_->bed() : nullptr; }
  cl::Buffer& rain_weight() { return rain_weight_; }
  // Σ rain weight over the vertices: the number of vertices rain falls on in full.
  double rained_vertices() const { return rained_vertices_; }

  ComputeContext& compute_;
  Parameters params_;
  GridState state_;
  std::unique_ptr<Ground> ground_;
  cl::Buffer placeholder_, rain_weight_;
  RainMask rain_mask_;
  double rained_vertices_ = 0;

 private:
  double time_ = 0, rain_time_ = 0;
  std::uint64_t steps_ = 0;
  std::vector<RainDisc> painted_;
  bool global_rain_ = true;
};

// The value of counter `name` in a restored list; throws an input error if it is missing.
std::int64_t counter_value(const std::vector<std::pair<std::string, std::int64_t>>& counters,
                           const std::string& name);
// The same, or `absent` for a counter that files written before it existed do not hold.
std::int64_t counter_value_or(const std::vector<std::pair<std::string, std::int64_t>>& counters,
                              const std::string& name, std::int64_t absent);

}  // namespace runnel
