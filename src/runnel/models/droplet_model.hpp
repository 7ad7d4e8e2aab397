// SPDX-License-Identifier: MIT
#pragma once
#include <array>
#include <cstdint>
#include <string>

#include "runnel/models/droplet_blocks.hpp"
#include "runnel/models/grid_model.hpp"

namespace runnel {

// Beyer 2015's droplet model (models.md), parameters with the widely used defaults.
struct DropletSettings {
  // The droplet.* parameters (defaults, units, meaning: the table in droplet_model.cpp).
  double radius;  // cells, erosion brush
  double inertia;
  double capacity;      // capacity factor
  double min_capacity;  // m of height
  double erode, deposit, evaporate;
  double gravity;
  int lifetime;  // steps
  double initial_water, initial_speed;
  std::int64_t batch;  // droplets per batch (moving in lockstep, step by step); 0: cells/64
  double volume;       // m³ of rain per droplet; 0: cell³

  static DropletSettings from(const Parameters& params);
  // Droplets a batch on a terrain of `vertices`: droplet.batch, or one per 64 vertices.
  long long batch_for(long long vertices) const;
  std::string build_options() const;
};

// Erosion_Beyer2015: particle droplets (Beyer 2015), host side of cl/models/droplet.cl. Each step
// runs one batch of droplets in parallel, in lockstep: every droplet step is a move over the
// heights as they stand and then the application of its fixed-point changes, exactly conserving
// volume: what leaves the map is counted as outflow.
class DropletModel final : public GridModel {
 public:
  static const ModelInfo& model_info();
  DropletModel(ComputeContext& compute, const Parameters& params, const Heightmap& terrain);
  // With droplet_apply's blocks cut as `blocks` says instead of for this device (tests: the result
  // does not depend on the cut).
  DropletModel(ComputeContext& compute, const Parameters& params, const Heightmap& terrain,
               const DropletBlocks& blocks);
  const ModelInfo& info() const override { return model_info(); }

  std::uint64_t droplets() const { return droplets_; }
  // Droplets per batch (droplet.batch, or one per 64 cells).
  long long batch_size() const;
  // Droplets a plane of the per-droplet buffers holds: the batch, padded to whole vectors of
  // droplet_move.
  long long plane_stride() const;
  long long outflow_quanta() override;  // height quanta carried out of the map
  long long droplets_out();             // droplets that left the map
  long long droplets_fallen();          // droplets the rain mask let fall (all without one)
  // m³ of rain one droplet stands for (droplet.volume, or cell³).
  double droplet_volume() const;
  // The droplets that fell (all of them, or those the rain mask let fall).
  double rain_volume() override {
    return droplet_volume() * static_cast<double>(droplets_fallen());
  }
  JsonObject diagnostics() override;
  double step_work() override {
    return static_cast<double>(batch_size()) * static_cast<double>(settings_.lifetime);
  }
  const char* work_unit() const override { return "droplet_steps"; }
  bool paints_rain() const override { return true; }

 protected:
  double take_step() override;
  void paint(double dt) override;
  std::vector<std::pair<std::string, std::int64_t>> counters() override;
  void restore_counters(const std::vector<std::pair<std::string, std::int64_t>>& c) override;
  double scratch_bytes() const override;

 private:
  std::array<cl_long, 3> read_counters();
  void run_batch(cl_uint count, float spawn_x, float spawn_z, float spawn_radius);
  void order_by_place(cl_uint count);
  DropletSettings settings_;
  std::uint64_t seed_;
  std::uint64_t droplets_ = 0;
  DropletBlocks blocks_;  // what droplet_apply's work-items take
  Kernel spawn_kernel_, move_kernel_, bin_kernel_, apply_kernel_;
  cl::Buffer counters_;  // {droplets out, outflow quanta, droplets the rain mask kept from falling}
  cl::Buffer droplet_state_, droplet_load_;  // per droplet of a batch, between its steps
  // Per droplet, from droplet_move through droplet_bin to droplet_apply: its old place, its
  // changes, its block and number there.
  cl::Buffer plan_place_, plan_, plan_bin_;
  cl::Buffer block_count_, block_start_, block_list_;  // the droplets with changes, by block
};

}  // namespace runnel
