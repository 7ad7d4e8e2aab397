// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <string>

#include "runnel/compute/context.hpp"
#include "runnel/compute/kernel.hpp"
#include "runnel/io/json.hpp"
#include "runnel/sim/parameters.hpp"
#include "runnel/sph/sph_solver.hpp"

namespace runnel {

// The rain of one run, resolved from the rain.* parameters and the terrain (no "auto" left).
struct RainSettings {
  enum class Region { kTerrain = 0, kRectangle = 1, kDisc = 2 };
  Region region = Region::kTerrain;
  double a = 0, b = 0, c = 0, d = 0;  // rectangle x0, x1, z0, z1, or disc x, radius, z
  double area = 0;                    // m²
  double rate = 0;                    // particles/s
  double intensity_mm_h = 0;          // the same rate as rain depth per hour
  double spawn_height = 0;            // m
  double speed = 0;                   // m/s
  long long max_particles = 0;
  double lifespan = 0;  // s
  double lifespan_jitter = 0;
  bool enabled = true;

  // `reference_speed` (m/s) and the particle spacing fill the automatic values.
  static RainSettings from(const Parameters& p, const DeviceTerrain& terrain, double spacing,
                           double reference_speed);
  JsonObject json() const;
};

// Host side of cl/rain.cl: spawns the particles of each step on the device. The count per step
// carries its fraction over (deterministic double arithmetic) and respects the particle budget;
// particle k of the run draws from counter k, so a resumed run spawns what an uninterrupted one
// would.
class RainEmitter {
 public:
  RainEmitter(ComputeContext& compute, const RainSettings& settings, std::uint64_t seed,
              float rest_density);
  // Spawns this step's rain into the solver. Returns the number spawned.
  std::size_t emit(SphSolver& solver, double dt);

  RainSettings& settings() { return settings_; }
  std::uint64_t spawned() const { return spawned_; }
  double carry() const { return carry_; }
  void restore(std::uint64_t spawned, double carry) {
    spawned_ = spawned;
    carry_ = carry;
  }

 private:
  ComputeContext& compute_;
  RainSettings settings_;
  std::uint64_t seed_;
  float rest_density_;
  Kernel kernel_;
  std::uint64_t spawned_ = 0;
  double carry_ = 0.0;
};

}  // namespace runnel
