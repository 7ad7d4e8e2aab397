// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <memory>

#include "runnel/compute/context.hpp"
#include "runnel/core/heightmap.hpp"
#include "runnel/sph/particle_store.hpp"
#include "runnel/sph/pressure/pressure_solver.hpp"
#include "runnel/sph/spatial_hash.hpp"
#include "runnel/sph/sph_settings.hpp"
#include "runnel/terrain/device_terrain.hpp"

namespace runnel {

// Events counted on the device (64-bit integer atomics: the counts do not depend on order).
// The order is the one of cl/counters.cl.
struct SphCounters {
  long long surface_projections = 0;   // particles found below the terrain and put back on it
  long long outflow_particles = 0;     // particles that left an open domain edge
  long long collisions = 0;            // arrivals on the terrain (contact events)
  long long outflow_sediment = 0;      // sediment quanta carried out through open edges
  long long evaporated_particles = 0;  // particles removed at the end of their lifespan
  long long lost_sediment = 0;         // quanta not deposited on evaporation (deposit_fraction < 1)
};
inline constexpr int kCounterCount = 6;

// The program of the SPH pipeline's kernels (integrate, forces, continuity, water depth) for these
// settings on a terrain of this cell size; kept by the context, built once.
cl::Program& sph_program(ComputeContext& compute, const SphSettings& settings, double terrain_cell);

// Sets the drift's outputs for the continuity pass (midpoints, drift velocities, volumes: the
// store's spare buffers) as the arguments of the drift or continuity kernel `k`.
void bind_continuity_inputs(ParticleStore& store, Kernel& k);

// Launches bed_friction_factors (`factors`) over the store's particles, into the scratch buffer
// of ρ (free until the continuity pass writes ρ(n+1) there), and sets it as the drift's friction.
void launch_bed_friction_factors(ParticleStore& store, Kernel& factors, Kernel& drift);

// The SPH solver (physics.md §2) on a terrain floor with an adaptive time step: the pipeline every
// pressure solver shares (host code of cl/integrate.cl with cl/collide.cl, and of
// cl/water_depth.cl), with the pressure solver sph.solver names (PressureSolver, registered in
// pressure/registry.cpp: wcsph, weakly compressible; dfsph, incompressible; docs/sph.md).
class SphSolver {
 public:
  // `top` is the highest y the fluid is expected to reach (m): the hash grid spans the terrain's
  // footprint from below its lowest point to `top`; particles above are clamped into the top cells.
  // `height_quantum` (m) is the fixed-point quantum of the terrain's heights.
  SphSolver(ComputeContext& compute, const SphSettings& settings, const Heightmap& floor,
            double top, double height_quantum = 1e-6);

  ParticleStore& particles() { return store_; }
  DeviceTerrain& terrain() { return terrain_; }
  // The water depth on the terrain's vertices, in counts of 1 µm (cl/water_depth.cl: the fine
  // field first, then the films' coarser levels), as the last depth pass measured it.
  const cl::Buffer& water_field() const { return water_; }
  float terrain_cell() const { return terrain_.cell(); }
  SpatialHash& hash() { return hash_; }
  const SphSettings& settings() const { return settings_; }

  // Appends particles (ids assigned); their rates are computed at the next step.
  void add(HostParticles particles);

  // One adaptive time step: drift() then complete_step(). Throws runnel::Error naming the step and
  // the cause on NaN/inf, a density outside the sane range, or a time step below dt_min.
  void step();
  // The two halves of a step, for callers that act between them (erosion, terrain changes, rain):
  // drift() kicks, integrates the continuity equation and the positions over dt and resolves
  // terrain contact; complete_step() rebuilds the hash, computes the accelerations, kicks again,
  // advances the clock and chooses the next dt.
  void drift();
  void complete_step();
  // The water depth D every step (0, the default), or only before the steps whose clock crosses a
  // multiple of `seconds` (an erosion exchange interval: those steps exchange with the bed and read
  // a fresh D); in between, each particle's D rides along the sort and the bed friction reads it
  // as last measured, and drops rained since then read 0 (docs/erosion.md, "Exchange interval").
  void measure_depth_every(double seconds);
  // The water field (water_field()) measured at every step's end even where the particles' depth
  // waits for the exchanges (measure_depth_every): the rain above the water reads it.
  void keep_water_field_current(bool every_step) { water_field_every_step_ = every_step; }
  // Puts particles the terrain rose under back on its surface (after erosion and talus).
  void project_to_surface();
  // After the terrain's heights were replaced between steps (a coupler's new heights): the
  // particles go back on the surface and the next step rebuilds the cell tables, as a restored
  // state does, so a run resumed from a checkpoint written here continues exactly.
  void terrain_replaced();
  // Computes the accelerations and the next time step for the current state without advancing.
  void prepare();

  double time() const { return time_; }
  double dt() const { return dt_; }
  // Shortens the next step to at most `most` s (a shorter step than the limits chose is stable);
  // first computes the rates and the step the limits choose, as the step would.
  void limit_dt(double most) {
    if (!rates_ready_) prepare();
    if (most > 0 && most < dt_) dt_ = most;
  }
  std::uint64_t steps() const { return steps_; }
  void restore_clock(double time, double dt, std::uint64_t steps);
  const SphHealth& health() const { return health_; }
  SphCounters counters();
  void restore_counters(const SphCounters& counters);
  cl::Buffer& counters_buffer() { return counters_buffer_; }
  const PressureSolver& pressure_solver() const { return *pressure_; }
  // Which solver ran, and its solves' counts where it has solves: what a run's report records.
  JsonObject solver_json() const { return pressure_->json(); }
  // Device memory a particle of capacity takes: the store's fields and the pressure solver's.
  std::size_t bytes_per_particle() const {
    return ParticleStore::bytes_per_particle() + pressure_->bytes_per_particle();
  }
  // Each particle's pressure (Pa), as the pressure solver found it.
  std::vector<float> pressure() { return pressure_->pressure(store_); }

 private:
  void drift_and_collide();
  void measure_water_depth();
  // The fine water field alone (no films' levels, no particle depths); false without particles.
  bool scatter_water();
  // The particles' x, z and ids and the water field, for its scatter and gather passes.
  void bind_water_field(Kernel& k);
  void coarsen_water(int levels);
  SphPipeline pipeline() { return {store_, hash_, terrain_}; }
  void build_hash();  // the two halves below at once
  // The hash build in two halves (SpatialHash::begin_build): work that does not need the live
  // count or the tiles goes between them, while the device reads them for the host.
  void sort_particles();
  void drop_dead_particles();
  // The step statistics (and, with closing_kick, v += a·dt/2 before them) and the next dt.
  void choose_next_dt(bool closing_kick = false);

  ComputeContext& compute_;
  SphSettings settings_;
  DeviceTerrain terrain_;
  ParticleStore store_;
  SpatialHash hash_;
  std::unique_ptr<PressureSolver> pressure_;
  Kernel drift_, friction_factors_, stats_, project_, depth_scatter_, depth_scatter_runs_,
      depth_gather_, depth_coarsen_;
  // Water on each terrain vertex, counts of 1 µm of depth, then its coarser levels for the films
  // (cl/water_depth.cl).
  cl::Buffer water_;
  bool water_field_every_step_ = false;
  cl::Buffer stats_buffer_, counters_buffer_;
  cl_uint stat_blocks_;           // step_stats' rows at most (a CPU: a few, a GPU: many)
  std::vector<float> stat_rows_;  // their values, read each step
  bool rates_ready_ = false;
  bool hash_stale_ = true;
  double time_ = 0.0;
  double dt_ = 0.0;
  double depth_interval_ = 0.0;  // s; 0: D every step
  std::uint64_t steps_ = 0;
  SphHealth health_;
};

}  // namespace runnel
