// SPDX-License-Identifier: MIT
#pragma once
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "runnel/compute/context.hpp"
#include "runnel/compute/kernel.hpp"
#include "runnel/core/parameters.hpp"
#include "runnel/io/json.hpp"
#include "runnel/sph/sph_solver.hpp"

namespace runnel {

// The rain of one run, resolved from the rain.* parameters and the terrain (no "auto" left).
struct RainSettings {
  // The rain.* parameters (defaults, units, meaning: the table in rain_emitter.cpp); from()
  // resolves the automatic ones (0) in place.
  std::string region_name;  // "terrain", "rectangle" or "disc"
  double rect_x0, rect_x1, rect_z0, rect_z1;
  double disc_x, disc_z, disc_radius;
  double rate;            // particles/s
  double intensity_mm_h;  // the same rate as rain depth per hour
  double spawn_height;    // m
  bool above_water;       // the spawn height is above the water's surface, not the terrain
  double speed;           // m/s
  std::int64_t max_particles;
  // rain.max_particles was 0: the budget follows the storm (rate × the longest lifespan), so no
  // drop of a storm given by rain.rate or rain.intensity is held back.
  bool budget_follows_storm = false;
  double lifespan;  // s
  double lifespan_jitter;
  bool enabled;
  // Resolved: what the kernel reads.
  // kMask: the whole terrain, by a rain mask (ground.rain_mask; set by RainEmitter).
  enum class Region { kTerrain = 0, kRectangle = 1, kDisc = 2, kMask = 3 };
  Region region;
  double a, b, c, d;  // rectangle x0, x1, z0, z1, or disc x, radius, z
  double area;        // m²

  // rain.spawn_height resolved: 0 is one particle spacing. The model needs it before from() (the
  // reference speed is the fall from there).
  static double spawn_height_of(const Parameters& p, double spacing);
  // `reference_speed` (m/s) and the particle spacing fill the automatic values.
  static RainSettings from(const Parameters& p, const DeviceTerrain& terrain, double spacing,
                           double reference_speed);
  JsonObject json() const;
  // The most drops that can be alive at once: those spawned over the longest lifespan.
  double most_alive() const { return std::ceil(rate * lifespan * (1.0 + lifespan_jitter)) + 1.0; }
  // Rain of `intensity_mm_h` on the disc (x, z, radius), as rain.region = "disc" would resolve it
  // with that rain.intensity (the viewer's brush).
  void rain_on_disc(double x, double z, double radius, double intensity, double spacing);
};

// The particle budget when neither the storm nor the budget is given: the rain is then
// budget / lifespan particles a second.
inline constexpr std::int64_t kDefaultRainBudget = 20000;

// The cumulative share of the rain through each cell of a terrain nx × ny (cells row-major,
// (nx − 1)·(ny − 1) of them), from the vertex weights: a cell weighs the mean of its corners. The
// second value is the mean cell weight, the fraction of the terrain's rain that falls.
std::pair<std::vector<float>, double> rain_cell_cdf(const std::vector<float>& weights, int nx,
                                                    int ny);

// Host side of cl/rain.cl: spawns the particles of each step on the device. The count per step
// carries its fraction over (deterministic double arithmetic) and respects the particle budget;
// particle k of the run draws from counter k, so a resumed run spawns what an uninterrupted one
// would.
class RainEmitter {
 public:
  // `rain_weights`: the rain mask's fraction per vertex of a terrain `nx` wide (empty: none). With
  // one, the rain of the whole terrain falls by it: the rate times the mean cell weight, each drop
  // in a cell drawn in proportion to the cell's weight (the mean of its corners) and uniformly
  // inside it.
  RainEmitter(ComputeContext& compute, const RainSettings& settings, std::uint64_t seed,
              float rest_density, const std::vector<float>& rain_weights = {}, int nx = 0);
  // Spawns this step's rain into the solver. Returns the number spawned.
  std::size_t emit(SphSolver& solver, double dt);

  RainSettings& settings() { return settings_; }
  const RainSettings& settings() const { return settings_; }
  // A new rain mask (same size; runnel-viewer paints it): the drawing distribution and the mask
  // rain's rate follow. The settings change only while they rain by the mask; masked_rain() is
  // the mask's rain whatever the settings are now.
  void set_weights(const std::vector<float>& rain_weights, int nx);
  const RainSettings& masked_rain() const { return masked_; }
  // The scenario's rain, without a mask.
  const RainSettings& scenario_rain() const { return unmasked_; }
  std::uint64_t spawned() const { return spawned_; }
  // Drops the rain asked for that rain.max_particles kept from falling (the store was full).
  std::uint64_t held_back() const { return held_back_; }
  double carry() const { return carry_; }
  void restore(std::uint64_t spawned, double carry, std::uint64_t held_back) {
    spawned_ = spawned;
    carry_ = carry;
    held_back_ = held_back;
  }

 private:
  ComputeContext& compute_;
  RainSettings settings_;
  RainSettings unmasked_, masked_;  // the scenario's rain without and with the mask
  std::uint64_t seed_;
  float rest_density_;
  Kernel kernel_;
  cl::Buffer cell_cdf_;  // the rain mask's cumulative share per cell (one 1 without a mask)
  int cells_ = 1;
  std::uint64_t spawned_ = 0;
  std::uint64_t held_back_ = 0;
  double carry_ = 0.0;
};

}  // namespace runnel
