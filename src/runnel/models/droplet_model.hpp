// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <string>

#include "runnel/compute/context.hpp"
#include "runnel/sim/parameters.hpp"
#include "runnel/terrain/device_terrain.hpp"

namespace runnel {

// Beyer 2015's droplet model (models.md), parameters with the widely used defaults.
struct DropletSettings {
  double radius = 3;  // cells, erosion brush
  double inertia = 0.05;
  double capacity = 4;         // capacity factor
  double min_capacity = 0.01;  // m of height
  double erode = 0.3, deposit = 0.3, evaporate = 0.01;
  double gravity = 4;
  int lifetime = 30;  // steps
  double initial_water = 1, initial_speed = 1;
  long long batch =
      0;  // droplets per batch (they read the terrain as at the batch start); 0: cells/64

  static DropletSettings from(const Parameters& params);
  std::string build_options() const;
};

// Erosion_Beyer2015: host side of cl/models/droplet.cl. Each advance() runs one batch of droplets
// in parallel and applies their fixed-point changes once, exactly conserving volume: what leaves
// the map is counted as outflow.
class DropletModel {
 public:
  DropletModel(ComputeContext& compute, DeviceTerrain& terrain, const DropletSettings& settings,
               std::uint64_t seed);
  void advance();

  std::uint64_t droplets() const { return droplets_; }
  long long outflow_quanta();  // height quanta carried out of the map
  long long droplets_out();    // droplets that left the map

 private:
  ComputeContext& compute_;
  DeviceTerrain& terrain_;
  DropletSettings settings_;
  std::uint64_t seed_;
  std::uint64_t droplets_ = 0;
  cl::Kernel kernel_;
  cl::Buffer counters_;
};

}  // namespace runnel
