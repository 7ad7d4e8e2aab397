// SPDX-License-Identifier: MIT
#pragma once
#include <cstddef>
#include <vector>

#include "runnel/io/json.hpp"
#include "runnel/sph/particle_store.hpp"
#include "runnel/sph/spatial_hash.hpp"
#include "runnel/terrain/device_terrain.hpp"

namespace runnel {

// Health of the particle state after a step, from the step_stats kernel.
struct SphHealth {
  double v_max = 0, a_max = 0;      // m/s, m/s²
  double rho_min = 0, rho_max = 0;  // kg/m³
  double drho_max = 0;              // kg/m³/s
  long long nonfinite = 0;          // particles with NaN or inf
};

// What a pressure solver's passes work on: the particles, sorted by the hash, and the terrain.
struct SphPipeline {
  ParticleStore& store;
  const SpatialHash& hash;
  DeviceTerrain& terrain;
};

// A method of keeping the water incompressible (or nearly so): the passes of an SPH step that
// depend on how pressure is found. SphSolver runs the shared pipeline (hash, rain, drift, terrain
// contact, bed friction, films, erosion) and calls these at fixed points of its step:
//
//   prepare:        measure_rates                     (a(n) at x(n))
//   drift:          before_drift(dt)  [drift: v(n+½), x(n+1) into scratch]  after_drift(dt)
//   complete_step:  [sort at x(n+1)]  complete(dt)    (a(n+1), and v(n+1) when the solver sets it)
//                   [step_stats, with the closing kick when closing_kick_in_stats()]  next_dt
//
// Each method lives in a folder of its own beside this file and is named once, in registry.cpp.
class PressureSolver {
 public:
  virtual ~PressureSolver() = default;

  // The accelerations (and the method's own per-particle state) at the hashed state.
  virtual void measure_rates(SphPipeline& p) = 0;
  // After the cell tables were rebuilt for a restored state, in the same order: what the method
  // keeps per listed neighbour must be measured again.
  virtual void rehashed(SphPipeline&) {}
  // Before the drift over dt (e.g. the impulse that keeps the density at ρ0 over it).
  virtual void before_drift(SphPipeline&, double /*dt*/) {}
  // After the drift wrote x(n+1) into the store's scratch: makes the new state current.
  virtual void after_drift(SphPipeline& p, double dt) = 0;
  // After the sort at x(n+1): a(n+1), and v(n+1) unless the step's statistics pass gives the
  // closing kick (closing_kick_in_stats()).
  virtual void complete(SphPipeline& p, double dt) = 0;
  virtual bool closing_kick_in_stats() const = 0;

  // The next time step after a step that left the particles in `health`, before sph.dt_max and
  // sph.dt_min are applied; and the step taken while there is no fluid yet.
  virtual double next_dt(const SphHealth& health) const = 0;
  virtual double first_dt() const = 0;
  // Whether a density below sph.density_min is a sign of trouble (a continuity density), or just
  // water thinning at a free surface (a summation density).
  virtual bool density_floor_checked() const = 0;

  // Each particle's pressure (Pa) in the last step.
  virtual std::vector<float> pressure(ParticleStore& store) const = 0;
  // The method's name, and its solves' counts where it has solves: what a run's report records.
  virtual JsonObject json() const = 0;
  // Device memory a particle of capacity takes beyond the store's fields, and what those buffers
  // hold now.
  virtual std::size_t bytes_per_particle() const { return 0; }
  virtual std::size_t allocated_bytes() const { return 0; }
  // The per-particle state the method keeps between steps: the sort carries it, a checkpoint
  // stores it, a resumed run restores it.
  virtual std::vector<ParticleField> kept_fields() const { return {}; }
};

}  // namespace runnel
